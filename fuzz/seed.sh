#!/usr/bin/env bash
# Seeds the fuzz corpora (fuzz/corpus/TARGET/, not committed) from the repository's fixtures,
# so each target starts from inputs of the right shape instead of from nothing.
# Usage: bash fuzz/seed.sh   (idempotent; existing corpus entries are kept)
set -euo pipefail
cd "$(dirname "$0")/.."
c=fuzz/corpus
mkdir -p "$c"/{csv_probe,number,piga_table,study_ron,scenario_ron,strd,lstsq,harmonics_analyze,piga_recording,binary}

# csv_probe: the first byte picks the format (0 = comma, µm, degrees); then a recording.
# The committed recordings are cut to their first 200 lines: the shape matters, not the length.
n=0
for f in fixtures/recordings/*.csv fixtures/recordings/*/probe_*.csv; do
  n=$((n + 1))
  { printf '\000'; head -n 200 "$f"; } > "$c/csv_probe/fixture-$n"
done
printf '\001time_s;gap_um;angle_deg\n0;1;0\n0.001;"2";1\n' > "$c/csv_probe/semicolon"
printf '\002time_s gap_um\r\n0  1\r\n0.001  2\r\n' > "$c/csv_probe/blank-crlf"

# number: fields of the fixtures and the parser's edge cases.
i=0
for s in 0 -0 1.5 +2 .5 5. 1e22 1e23 9007199254740993 0.1e-22 1e-400 1e400 \
         12345678901234567890 47.270448 -3.2e-7 nan inf -infinity 1e 1e+ 0x10 ' 7 '; do
  i=$((i + 1)); printf '%s' "$s" > "$c/number/n$i"
done

# piga_table: the committed table and small variants.
cp fixtures/recordings/pre-balance-small/piga.csv "$c/piga_table/fixture"
printf '# c\nrate_deg_s,output_rad_s\n10,0.5\n\n20,"1.5e-1"\n' > "$c/piga_table/comments"

cp fixtures/studies/*.ron "$c/study_ron/"
cp fixtures/scenarios/*.ron "$c/scenario_ron/"

# strd: the NIST datasets when ../shared has them (they are not part of the repository).
if [ -d ../shared/reference/nist-strd ]; then
  cp ../shared/reference/nist-strd/*.dat "$c/strd/"
fi

# lstsq and harmonics_analyze read raw bytes: a few deterministic byte strings.
for k in 1 2 3 4; do
  head -c $((64 * k)) fixtures/recordings/probe_120deg_s.csv > "$c/lstsq/bytes-$k"
  head -c $((2048 * k)) fixtures/recordings/probe_120deg_s.csv > "$c/harmonics_analyze/bytes-$k"
done
# piga_recording: the first byte picks the unit, order and rate (0 = rad, order 1, 1 deg/s;
# 0x80 = 100 deg/s); then a raw output recording of the campaign.
for f in fixtures/campaign/piga_100.0000deg_s.csv fixtures/campaign/piga_200.0000deg_s.csv; do
  n=$(basename "$f" .csv)
  { printf '\200'; head -n 300 "$f"; } > "$c/piga_recording/fixture-$n"
done
# binary: the first byte picks the reader (bit 0: MAT), the group (bit 1: top level) and
# the time channel (bit 2: none), the DAQmx fixtures' channel names (bit 3); then the
# fixtures written by npTDMS, scipy and make_daqmx.py.
for f in fixtures/recordings/binary/daqmx_*.tdms; do
  { printf '\010'; cat "$f"; } > "$c/binary/$(basename "$f")"
done
for f in fixtures/recordings/binary/probe_*.tdms; do
  { printf '\000'; cat "$f"; } > "$c/binary/$(basename "$f")"
  { printf '\004'; cat "$f"; } > "$c/binary/no-time-$(basename "$f")"
done
for f in fixtures/recordings/binary/*.mat; do
  { printf '\001'; cat "$f"; } > "$c/binary/$(basename "$f")"
done
echo "seeded $(find "$c" -type f | wc -l) corpus files under $c"

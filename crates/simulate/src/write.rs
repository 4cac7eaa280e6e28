//! Writing a simulation's files: probe recordings, `piga.csv`, the mountings' tables
//! (`piga_ia_in.csv`, `piga_ia_out.csv`), `truth.json`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use edge_io::OutputSet;
use recording::{
    PIGA_OUTPUT_COLUMN, PIGA_RATE_COLUMN, ProbeColumns, WriteOptions, write_probe_csv,
};

use super::generate::{PigaRow, SimulatedPigaRecording, SimulatedRecording, Simulation};
use crate::error::{Result, SimulateError};

/// The files a simulation wrote.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SimulationFiles {
    /// One probe recording per rate, in the scenario's order, then the second probe's.
    pub recordings: Vec<PathBuf>,
    /// `piga.csv`.
    pub piga_csv: PathBuf,
    /// One raw PIGA output recording per rate, when the scenario asks for them (then the
    /// further mountings' ones).
    pub piga_recordings: Vec<PathBuf>,
    /// The further mountings' tables (`piga_ia_in.csv`, `piga_ia_out.csv`), in the
    /// scenario's order.
    pub mounting_tables: Vec<PathBuf>,
    /// `truth.json`.
    pub truth_json: PathBuf,
}

/// The names a simulation's output directory may hold: what [`write_simulation`] writes.
const SIMULATION_FILES: &[&str] = &[
    "probe_*deg_s.csv",
    "piga_*deg_s.csv",
    "probe2_*deg_s.csv",
    "piga.csv",
    "piga_ia_in.csv",
    "piga_ia_out.csv",
    "truth.json",
];

/// Writes a simulation into `dir`, atomically: `probe_<rate>deg_s.csv` per rate, `piga.csv`
/// and `truth.json` go through an [`OutputSet`], so `dir` ends up holding exactly these files
/// (recordings of an earlier scenario's other rates are removed) or, on any error, what it
/// held before, byte for byte.
///
/// # Errors
/// [`SimulateError::File`] when `dir` holds files a simulation does not write, or a file
/// cannot be written or moved into place (naming it); [`SimulateError::Serialize`] if
/// `truth.json` cannot be serialised (nothing is written).
pub fn write_simulation(dir: &Path, sim: &Simulation) -> Result<SimulationFiles> {
    let json =
        edge_io::to_json_pretty(&sim.truth).map_err(|e| SimulateError::json("truth.json", e))?;
    edge_io::check_finite(&sim.piga).map_err(|e| SimulateError::NonFiniteOutput {
        what: "piga.csv",
        field: e.path,
        value: e.value,
    })?;
    let mut set = OutputSet::create(dir, SIMULATION_FILES)?;
    let mut recordings = Vec::with_capacity(sim.recordings.len());
    for r in sim.recordings.iter().chain(&sim.second_recordings) {
        recordings.push(set.write_with(&r.file_name, |mut out| r.write_csv(&mut out))?);
    }
    let mut piga_recordings = Vec::with_capacity(sim.piga_recordings.len());
    let mounted_recordings = sim.mountings.iter().flat_map(|m| &m.piga_recordings);
    for r in sim.piga_recordings.iter().chain(mounted_recordings) {
        piga_recordings.push(set.write(&r.file_name, r.csv_text().as_bytes())?);
    }
    let piga_csv = set.write("piga.csv", piga_csv_text(&sim.piga).as_bytes())?;
    let mut mounting_tables = Vec::with_capacity(sim.mountings.len());
    for m in &sim.mountings {
        edge_io::check_finite(&m.piga).map_err(|e| SimulateError::NonFiniteOutput {
            what: "a mounting's PIGA table",
            field: e.path,
            value: e.value,
        })?;
        mounting_tables.push(set.write(&m.file_name, piga_csv_text(&m.piga).as_bytes())?);
    }
    let truth_json = set.write("truth.json", json.as_bytes())?;
    set.commit()?;
    Ok(SimulationFiles {
        recordings,
        piga_csv,
        piga_recordings,
        mounting_tables,
        truth_json,
    })
}

/// The text of `piga.csv`: header `rate_deg_s,output_rad_s`, then one row per rate with
/// every number in its shortest exact (round-trip) decimal form.
///
/// ```
/// let rows = [simulate::PigaRow { rate_deg_s: 10.0, output_rad_s: 0.0041 }];
/// assert_eq!(simulate::piga_csv_text(&rows), "rate_deg_s,output_rad_s\n10,0.0041\n");
/// ```
#[must_use]
pub fn piga_csv_text(rows: &[PigaRow]) -> String {
    let mut text = format!("{PIGA_RATE_COLUMN},{PIGA_OUTPUT_COLUMN}\n");
    for r in rows {
        // writing to a String cannot fail
        let _ = writeln!(text, "{},{}", r.rate_deg_s, r.output_rad_s);
    }
    text
}

impl SimulatedPigaRecording {
    /// The recording as CSV: header `time_s,output_rad[,angle_deg]`, times and output angles
    /// in their shortest exact (round-trip) decimal form, angles with nine decimals (the
    /// probe recording's).
    #[must_use]
    pub fn csv_text(&self) -> String {
        let mut text = String::from("time_s,output_rad");
        if self.angle_deg.is_some() {
            text.push_str(",angle_deg");
        }
        text.push('\n');
        for (i, (t, o)) in self.time_s.iter().zip(&self.output_rad).enumerate() {
            // writing to a String cannot fail
            let _ = match &self.angle_deg {
                Some(a) => writeln!(text, "{t},{o},{:.9}", a[i]),
                None => writeln!(text, "{t},{o}"),
            };
        }
        text
    }
}

impl SimulatedRecording {
    /// Writes the recording as CSV in the probe-recording format
    /// ([`recording::write_probe_csv`]): header `time_s,gap_um[,angle_deg]`, then one row
    /// per sample; times, gaps and angles with nine decimals (ns, fm — far below any probe
    /// noise — and 1e-9 deg).
    ///
    /// # Errors
    /// Whatever `out` returns; [`std::io::ErrorKind::InvalidInput`] wrapping the
    /// [`recording::RecordingError`] if the columns differ in length or hold a value that
    /// is not finite (nothing is written then).
    pub fn write_csv<W: std::io::Write>(&self, out: &mut W) -> std::io::Result<()> {
        let columns = ProbeColumns::new(&self.time_s, &self.gap_um, self.angle_deg.as_deref())
            .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidInput, e))?;
        let options = WriteOptions {
            decimals: 9,
            header_comment: None,
        };
        write_probe_csv(out, &columns, &options)
    }
}

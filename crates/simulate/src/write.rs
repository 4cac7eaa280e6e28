//! Writing a simulation's files: probe recordings, `piga.csv`, `truth.json`.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use recording::{
    PIGA_OUTPUT_COLUMN, PIGA_RATE_COLUMN, ProbeColumns, WriteOptions, write_probe_csv,
};

use super::generate::{PigaRow, SimulatedRecording, Simulation};
use crate::error::{Result, SimulateError};

/// The files a simulation wrote.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SimulationFiles {
    /// One probe recording per rate, in the scenario's order.
    pub recordings: Vec<PathBuf>,
    /// `piga.csv`.
    pub piga_csv: PathBuf,
    /// `truth.json`.
    pub truth_json: PathBuf,
}

/// Writes a simulation into `dir` (created if needed): `probe_<rate>deg_s.csv` per rate,
/// `piga.csv` and `truth.json`. Existing files of the same names are replaced.
///
/// # Errors
/// [`SimulateError::Io`] naming the file that could not be written;
/// [`SimulateError::Serialize`] if `truth.json` cannot be serialised.
pub fn write_simulation(dir: &Path, sim: &Simulation) -> Result<SimulationFiles> {
    std::fs::create_dir_all(dir).map_err(|source| SimulateError::Io {
        path: dir.to_owned(),
        source,
    })?;
    let mut recordings = Vec::with_capacity(sim.recordings.len());
    for r in &sim.recordings {
        let path = dir.join(&r.file_name);
        write_recording(&path, r)?;
        recordings.push(path);
    }
    let piga_csv = dir.join("piga.csv");
    write_file(&piga_csv, piga_csv_text(&sim.piga).as_bytes())?;
    let truth_json = dir.join("truth.json");
    let json = serde_json::to_string_pretty(&sim.truth).map_err(|e| SimulateError::Serialize {
        what: "truth.json",
        message: e.to_string(),
    })?;
    write_file(&truth_json, json.as_bytes())?;
    Ok(SimulationFiles {
        recordings,
        piga_csv,
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

/// Writes one recording file (see [`SimulatedRecording::write_csv`]).
fn write_recording(path: &Path, r: &SimulatedRecording) -> Result<()> {
    let io = |source| SimulateError::Io {
        path: path.to_owned(),
        source,
    };
    let file = std::fs::File::create(path).map_err(io)?;
    let mut out = std::io::BufWriter::with_capacity(1 << 16, file);
    r.write_csv(&mut out).map_err(io)?;
    out.flush().map_err(io)
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

fn write_file(path: &Path, bytes: &[u8]) -> Result<()> {
    std::fs::write(path, bytes).map_err(|source| SimulateError::Io {
        path: path.to_owned(),
        source,
    })
}

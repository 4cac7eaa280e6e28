//! `init` on NI TDMS and MATLAB MAT files: the channels (variables) the recording crate's
//! readers list, their roles from their names, their units from the file's properties
//! (`unit_string`, `NI_UnitDescription`) or from their names, the time from a time channel
//! or the gap channel's waveform timing (`wf_increment`); the gap, the angle reference and
//! the rate then as for a text file.

use std::path::Path;

use recording::ChannelInfo;

use super::columns::{Column, Role};
use super::file::{Finding, Kind, PLACEHOLDER, Setting, signals, time_setting};

/// Understands a TDMS (`tdms`) or MAT file from its bytes into `f`.
pub(crate) fn understand(f: &mut Finding, bytes: &[u8], tdms: bool) {
    let path = f.path.clone();
    let (what, item) = if tdms {
        ("an NI TDMS", "channel")
    } else {
        ("a MATLAB", "variable")
    };
    let listed = if tdms {
        recording::list_tdms(bytes, &path)
    } else {
        recording::list_mat(bytes, &path)
    };
    let all = match listed {
        Ok(all) => all,
        Err(e) => {
            f.problems.push(format!(
                "cannot be read as {what} file: {}",
                strip_path(&e, &path)
            ));
            return;
        }
    };
    let column = |c: &ChannelInfo| {
        let mut col = Column::of(&c.name);
        if let Some(unit) = &c.unit {
            col.unit = Some(unit.clone());
        }
        col
    };
    let named = |c: &&ChannelInfo| {
        let prefix = c
            .group
            .as_deref()
            .map_or_else(String::new, |g| format!("{g}/"));
        format!("{prefix}{}", c.name)
    };
    // The group (or struct) holding a gap channel: the probe's.
    let Some(group) = all
        .iter()
        .find(|c| c.samples.is_some() && Column::of(&c.name).role == Role::Gap)
        .map(|c| c.group.clone())
    else {
        let names: Vec<String> = all.iter().map(|c| named(&c)).collect();
        let output = all.iter().any(|c| Column::of(&c.name).role == Role::Output);
        f.problems.push(if output {
            format!(
                "{what} file with a PIGA output {item}: PIGA output recordings are read from \
                 delimited text only; export them as CSV"
            )
        } else {
            format!(
                "unknown shape: no {item} named as a probe gap among {} (name it `gap`, \
                 `Gap`, `displacement`, `Spalt`, …)",
                if names.is_empty() {
                    "none".to_owned()
                } else {
                    names.join(", ")
                }
            )
        });
        return;
    };
    let chosen: Vec<&ChannelInfo> = all
        .iter()
        .filter(|c| c.group == group && c.samples.is_some())
        .collect();
    let columns: Vec<Column> = chosen.iter().map(|c| column(c)).collect();
    let header: Vec<String> = chosen.iter().map(|c| c.name.clone()).collect();
    f.kind = Some(Kind::Probe);
    if let Some(g) = &group {
        let others = all
            .iter()
            .filter_map(|c| c.group.as_deref())
            .filter(|o| o != g)
            .collect::<std::collections::BTreeSet<_>>();
        f.format.push(Setting::new(
            format!("group: {}", super::setting::ron_string(g)),
            format!(
                "the {} holding the {item}s {}{}",
                if tdms { "group" } else { "struct variable" },
                header.join(", "),
                if others.is_empty() {
                    String::new()
                } else {
                    format!(
                        " (the file's other groups: {})",
                        others.into_iter().collect::<Vec<_>>().join(", ")
                    )
                }
            ),
        ));
    }
    let read = |name: &str| -> Result<Vec<f64>, String> {
        let values = if tdms {
            recording::tdms_channel(bytes, &path, group.as_deref(), name)
        } else {
            recording::mat_variable(bytes, &path, group.as_deref(), name)
        };
        values.map_err(|e| strip_path(&e, &path))
    };
    let gap = chosen
        .iter()
        .find(|c| Column::of(&c.name).role == Role::Gap)
        .copied();
    let time_s = match time_setting(f, &columns, &read) {
        Some(time_s) => time_s,
        None => {
            // No time channel: the gap channel's waveform timing, or nothing.
            let waveform = gap.filter(|g| g.waveform);
            match waveform {
                Some(g) => {
                    let channels = recording::BinaryChannels {
                        group: group.clone(),
                        time: None,
                        gap: g.name.clone(),
                        angle: None,
                        ..recording::BinaryChannels::default()
                    };
                    let times = recording::parse_tdms(bytes, &path, &channels).map(|r| r.time_s);
                    f.format.push(Setting::new(
                        "waveform_time: true",
                        format!(
                            "no time {item}; `{}` carries NI waveform timing (wf_increment): \
                             the sample times are wf_start_offset + i·wf_increment",
                            g.name
                        ),
                    ));
                    if let Err(e) = &times {
                        f.problems.push(format!(
                            "its waveform timing cannot be read: {}",
                            strip_path(e, &path)
                        ));
                    }
                    times.ok()
                }
                None => {
                    f.format.push(Setting::new(
                        format!("time: (column: {PLACEHOLDER:?}, unit: s)"),
                        format!(
                            "no {item} named as a time and no waveform timing on the gap \
                             {item} ({item}s: {}): name the time {item}",
                            header.join(", ")
                        ),
                    ));
                    None
                }
            }
        }
    };
    signals(f, Kind::Probe, &columns, &header, &read, time_s.as_deref());
    // The evidence speaks of the file's channels (variables), not of a header.
    let source = |name: &str| {
        chosen
            .iter()
            .find(|c| c.name == name)
            .and_then(|c| c.unit.as_deref())
            .map_or_else(
                || match Column::of(name).unit {
                    Some(u) => format!("{item} `{name}` (the unit `{u}` in its name)"),
                    None => format!("{item} `{name}`"),
                },
                |u| format!("{item} `{name}` (the file's unit `{u}`)"),
            )
    };
    for s in &mut f.format {
        for name in &header {
            let phrase = format!("the header's `{name}`");
            if s.evidence.contains(&phrase) {
                s.evidence = s.evidence.replace(&phrase, &source(name));
            }
        }
    }
}

/// An error's text without the file's path in front (the table names the file).
fn strip_path(e: &dyn std::fmt::Display, path: &Path) -> String {
    let text = e.to_string();
    let prefix = format!("{}: ", path.display());
    text.strip_prefix(&prefix)
        .map_or_else(|| text.clone(), str::to_owned)
}

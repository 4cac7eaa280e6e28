//! A TDMS segment's metadata: the object list, each object's raw-data index (plain or
//! DAQmx) and its properties (waveform timing, `NI_Scaling`, units).

use crate::binary::channels::Cursor;
use crate::binary::daqmx;
use crate::binary::decode::decode;
use crate::binary::scaling::Prop;
use crate::error::{BinaryDefect, BinaryPart, Result};

use super::walk::{
    Index, NO_RAW_DATA, Object, SAME_RAW_INDEX, TYPE_STRING, Walk, num_type, value_size,
};

impl Walk<'_> {
    pub(super) fn metadata(&mut self, bytes: &[u8], start: usize) -> Result<()> {
        let place = self.place;
        let mut c = Cursor::based(bytes, start, BinaryPart::Metadata, place);
        let objects = c.u32()?;
        for _ in 0..objects {
            let at = c.pos();
            let path = string(&mut c)?;
            let k = self.object(&path);
            let index_len = c.u32()?;
            let index = match index_len {
                NO_RAW_DATA => None,
                SAME_RAW_INDEX => Some(
                    self.objects[k]
                        .last
                        .ok_or_else(|| place.malformed(at, BinaryDefect::NoPreviousIndex))?,
                ),
                daqmx::FORMAT_CHANGING | daqmx::DIGITAL_LINE => {
                    let d = daqmx::read_index(&mut c, index_len, at, place)?;
                    let index = Index {
                        code: d.data_type,
                        count: d.count,
                        bytes: None,
                        daqmx: Some(self.daqmx.len()),
                    };
                    self.daqmx.push(d);
                    Some(index)
                }
                20 | 28 => {
                    let code = c.u32()?;
                    let dim = c.u32()?;
                    if dim != 1 {
                        return Err(
                            place.malformed(at, BinaryDefect::ArrayDimension { found: dim })
                        );
                    }
                    let count = c.u64()?;
                    let bytes = if code == TYPE_STRING {
                        if index_len != 28 {
                            return Err(
                                place.malformed(at, BinaryDefect::IndexLength { found: index_len })
                            );
                        }
                        Some(c.u64()?)
                    } else {
                        if index_len != 20 {
                            c.u64()?;
                        }
                        value_size(code).and_then(|s| count.checked_mul(s))
                    };
                    Some(Index {
                        code,
                        count,
                        bytes,
                        daqmx: None,
                    })
                }
                found => return Err(place.malformed(at, BinaryDefect::IndexLength { found })),
            };
            let obj = &mut self.objects[k];
            obj.index = index;
            if index.is_some() {
                obj.last = index;
            }
            if let Some(i) = index.filter(|i| obj.wanted && i.daqmx.is_none())
                && num_type(i.code).is_none()
            {
                obj.bad_type.get_or_insert(i.code);
            }
            if let Some(d) = index.and_then(|i| i.daqmx) {
                obj.daqmx_type = Some(self.daqmx[d].data_type);
            }
            if !self.list.contains(&k) {
                self.list.push(k);
            }
            let properties = c.u32()?;
            for _ in 0..properties {
                let at = c.pos();
                let name = string(&mut c)?;
                let code = c.u32()?;
                let value = property(&mut c, code)
                    .transpose()
                    .ok_or_else(|| place.malformed(at, BinaryDefect::PropertyType { code }))??;
                let obj = &mut self.objects[k];
                let number = match &value {
                    Some(Prop::Num(x)) => Some(*x),
                    _ => None,
                };
                match name.as_str() {
                    "wf_increment" => obj.wf_increment = number,
                    "wf_start_offset" => obj.wf_start = number,
                    n if n.starts_with("NI_") || n == "unit_string" => {
                        if let Some(v) = value {
                            obj.props.push((name.clone(), v));
                        }
                    }
                    _ => {}
                }
            }
        }
        Ok(())
    }

    /// The object of a path, created on first sight; a channel that one of the roles
    /// names (in the group asked for, else in the first group that has it) is claimed.
    pub(super) fn object(&mut self, path: &str) -> usize {
        if let Some(&k) = self.by_path.get(path) {
            return k;
        }
        let k = self.objects.len();
        let name = channel_name(path);
        let mut wanted = self.all && name.is_some();
        if let Some((g, ch)) = &name
            && self.group.is_none_or(|want| want == g)
        {
            for (role, want) in self.roles.iter().enumerate() {
                if !want.is_empty() && want == ch && self.claimed[role].is_none() {
                    self.claimed[role] = Some(k);
                    wanted = true;
                }
            }
        }
        self.objects.push(Object {
            name,
            index: None,
            last: None,
            bad_type: None,
            wf_increment: None,
            wf_start: None,
            spans: Vec::new(),
            scalers: Vec::new(),
            daqmx_type: None,
            unsupported: None,
            props: Vec::new(),
            wanted,
        });
        self.by_path.insert(path.to_string(), k);
        k
    }
}

/// A length-prefixed UTF-8 string (invalid UTF-8 replaced).
fn string(c: &mut Cursor<'_>) -> Result<String> {
    let n = c.u32()?;
    Ok(String::from_utf8_lossy(c.take(u64::from(n))?).into_owned())
}

/// `(group, channel)` of an object path `/'group'/'channel'` (quotes doubled inside).
pub(super) fn channel_name(path: &str) -> Option<(String, String)> {
    let mut parts = Vec::new();
    let mut rest = path;
    while let Some(r) = rest.strip_prefix("/'") {
        let mut name = String::new();
        let mut chars = r.char_indices();
        let mut end = None;
        while let Some((i, ch)) = chars.next() {
            if ch == '\'' {
                if r[i + 1..].starts_with('\'') {
                    name.push('\'');
                    chars.next();
                } else {
                    end = Some(i + 1);
                    break;
                }
            } else {
                name.push(ch);
            }
        }
        parts.push(name);
        rest = &r[end?..];
    }
    match (rest.is_empty(), <[String; 2]>::try_from(parts)) {
        (true, Ok([g, c])) => Some((g, c)),
        _ => None,
    }
}

/// A property's value: `Some(Some(value))` a number or a string, `Some(None)` another known
/// type (skipped), `None` an unknown type.
fn property(c: &mut Cursor<'_>, code: u32) -> Result<Option<Option<Prop>>> {
    if code == TYPE_STRING {
        return Ok(Some(Some(Prop::Text(string(c)?))));
    }
    let Some(size) = value_size(code) else {
        return Ok(None);
    };
    let bytes = c.take(size)?;
    Ok(Some(num_type(code).map(|ty| {
        let mut v = [f64::NAN];
        decode(&mut v, bytes, ty, ty.size());
        Prop::Num(v[0])
    })))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn object_paths() {
        assert_eq!(
            channel_name("/'probe'/'gap_um'"),
            Some(("probe".into(), "gap_um".into()))
        );
        assert_eq!(
            channel_name("/'it''s'/'a''b'"),
            Some(("it's".into(), "a'b".into()))
        );
        assert_eq!(channel_name("/'probe'"), None);
        assert_eq!(channel_name("/"), None);
        assert_eq!(channel_name("/'a'/'b'/'c'"), None);
        assert_eq!(channel_name("/'a"), None);
    }
}

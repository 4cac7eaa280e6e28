//! Python values of a configuration (a study, plan or format given as a dict) as the
//! configuration's data, and the arguments a caller may get wrong, checked with the
//! package's errors.

use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use serde_json::Value;

use crate::errors::{self, Kind, Located};

/// Deepest nesting of dicts and lists a configuration may have: a study nests about eight
/// levels (a phase's points' format's angle's unit); a structure deeper than this, or one
/// that holds itself, is refused before it can exhaust the stack.
pub(crate) const MAX_DEPTH: usize = 64;

/// A Python value (dict, list, tuple, str, int, float, bool, None, a path, a numpy scalar
/// or array) as a configuration value, floats exactly (no text in between); `root` names
/// it in errors ([`Kind::Config`], with the field's path within it).
pub(crate) fn value(py: Python<'_>, obj: &Bound<'_, PyAny>, root: &str) -> PyResult<Value> {
    convert(py, obj, &Where { root, at: "" }, 0)
}

/// Where a value is: what is being read (`study`, `plan`, `format`) and the path within.
struct Where<'a> {
    root: &'a str,
    at: &'a str,
}

fn bad(py: Python<'_>, place: &Where<'_>, what: String) -> PyErr {
    let (root, at) = (place.root, place.at);
    let message = if at.is_empty() {
        format!("{root}: {what}")
    } else {
        format!("{root}: `{}`: {what}", short(at))
    };
    let field = if at.is_empty() {
        root.to_owned()
    } else {
        at.to_owned()
    };
    errors::raise(py, Kind::Config, message, Located::field(field))
}

/// A Python error met while reading a value (an object whose conversion raises) as the
/// package's; `KeyboardInterrupt` and other non-`Exception`s pass through.
fn wrapped(py: Python<'_>, e: PyErr, place: &Where<'_>) -> PyErr {
    if e.is_instance_of::<pyo3::exceptions::PyException>(py)
        && !e.is_instance(py, &py.get_type::<errors::CentrifugeCalError>())
    {
        bad(py, place, e.value(py).to_string())
    } else {
        e
    }
}

fn convert(
    py: Python<'_>,
    obj: &Bound<'_, PyAny>,
    place: &Where<'_>,
    depth: usize,
) -> PyResult<Value> {
    if depth > MAX_DEPTH {
        return Err(bad(
            py,
            place,
            format!(
                "nested more than {MAX_DEPTH} levels deep (a dict or list that holds itself?); \
                 a configuration nests a few levels"
            ),
        ));
    }
    if obj.is_none() {
        return Ok(Value::Null);
    }
    if obj.is_instance_of::<PyBool>() {
        return Ok(Value::Bool(obj.extract()?));
    }
    if obj.is_instance_of::<PyInt>() {
        if let Ok(i) = obj.extract::<i64>() {
            return Ok(Value::from(i));
        }
        if let Ok(u) = obj.extract::<u64>() {
            return Ok(Value::from(u));
        }
        return Err(bad(
            py,
            place,
            format!(
                "the integer {} is out of range (at most 2⁶⁴ − 1)",
                short(&obj.str().map_or_else(|_| String::new(), |s| s.to_string()))
            ),
        ));
    }
    if obj.is_instance_of::<PyFloat>() {
        let x: f64 = obj.extract()?;
        return serde_json::Number::from_f64(x)
            .map(Value::Number)
            .ok_or_else(|| bad(py, place, format!("{x} is not a finite number")));
    }
    if obj.is_instance_of::<PyString>() {
        return Ok(Value::String(obj.extract()?));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        let mut map = serde_json::Map::new();
        for (k, v) in d.iter() {
            let key: String = k.extract().map_err(|_| {
                bad(
                    py,
                    place,
                    format!(
                        "the key {} is not a string",
                        short(&k.repr().map_or_else(|_| String::new(), |r| r.to_string()))
                    ),
                )
            })?;
            let at = join(place.at, &key);
            let inner = convert(
                py,
                &v,
                &Where {
                    root: place.root,
                    at: &at,
                },
                depth + 1,
            )?;
            map.insert(key, inner);
        }
        return Ok(Value::Object(map));
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let mut out = Vec::new();
        for (i, v) in obj.try_iter()?.enumerate() {
            let v = v.map_err(|e| wrapped(py, e, place))?;
            let at = format!("{}[{i}]", place.at);
            out.push(convert(
                py,
                &v,
                &Where {
                    root: place.root,
                    at: &at,
                },
                depth + 1,
            )?);
        }
        return Ok(Value::Array(out));
    }
    let numpy = py.import("numpy")?;
    if obj.is_instance(&numpy.getattr("ndarray")?)? {
        if obj.is_instance(&numpy.getattr("ma")?.getattr("MaskedArray")?)? {
            return Err(bad(
                py,
                place,
                "a masked array: its masked values would be read as numbers; give the values \
                 to use (numpy.ma.compressed) or fill them"
                    .to_owned(),
            ));
        }
        let list = obj
            .call_method0("tolist")
            .map_err(|e| wrapped(py, e, place))?;
        return convert(py, &list, place, depth);
    }
    // a path (os.PathLike), or a numpy scalar (float64, int64, bool_): by its conversion
    if let Ok(p) = py.import("os")?.call_method1("fspath", (obj,)) {
        return Ok(Value::String(p.extract()?));
    }
    if obj.is_instance(&numpy.getattr("generic")?)? {
        let item = obj
            .call_method0("item")
            .map_err(|e| wrapped(py, e, place))?;
        return convert(py, &item, place, depth + 1);
    }
    Err(bad(
        py,
        place,
        format!(
            "a {} is not a configuration value (a dict, list, str, number, bool or None)",
            obj.get_type().name()?
        ),
    ))
}

fn join(at: &str, key: &str) -> String {
    if at.is_empty() {
        key.to_owned()
    } else {
        format!("{at}.{key}")
    }
}

/// A text cut to 60 characters, for a message.
fn short(text: &str) -> String {
    let mut chars = text.chars();
    let head: String = chars.by_ref().take(60).collect();
    if chars.next().is_some() {
        format!("{head}…")
    } else {
        head
    }
}

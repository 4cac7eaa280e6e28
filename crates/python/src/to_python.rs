//! Rust results as Python objects, straight from their `serde::Serialize` (no text in
//! between), in the shape `results.json` and `plan.json` give them: structs and maps as
//! dicts, sequences and tuples as lists, unit enum variants as their names, other variants
//! as one-key dicts, `None` for an absent value. A NaN or ±∞ anywhere is refused by its
//! path (`phases[0].fit.c_r_m_s2`), as the JSON writer refuses it (`edge_io::to_json_pretty`).

use std::fmt;

use pyo3::IntoPyObjectExt;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};
use serde::ser::{self, Serialize};

/// Why a value cannot become a Python object.
#[derive(Debug)]
pub(crate) enum ToPythonError {
    /// A number that is not finite, at its path.
    NonFinite { at: String, value: f64 },
    /// Python refused an object.
    Python(PyErr),
    /// The value's own `Serialize` failed.
    Custom(String),
}

impl fmt::Display for ToPythonError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite { at, value } => write!(
                f,
                "result `{at}` is not finite ({value}): the inputs take it out of the range of \
                 double precision"
            ),
            Self::Python(e) => write!(f, "{e}"),
            Self::Custom(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for ToPythonError {}

impl ser::Error for ToPythonError {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        Self::Custom(msg.to_string())
    }
}

impl From<PyErr> for ToPythonError {
    fn from(e: PyErr) -> Self {
        Self::Python(e)
    }
}

type Result<T> = std::result::Result<T, ToPythonError>;

/// Where a value is, as a chain of keys back to the root (built on the stack, written out
/// only for an error).
#[derive(Clone, Copy)]
enum Key<'a> {
    Field(&'static str),
    Index(usize),
    Name(&'a str),
}

#[derive(Clone, Copy)]
struct At<'a> {
    parent: Option<&'a At<'a>>,
    key: Key<'a>,
}

fn path(at: Option<&At<'_>>) -> String {
    let mut keys = Vec::new();
    let mut next = at;
    while let Some(a) = next {
        keys.push(a.key);
        next = a.parent;
    }
    let mut out = String::new();
    for key in keys.iter().rev() {
        match key {
            Key::Index(i) => out.push_str(&format!("[{i}]")),
            Key::Field(name) | Key::Name(name) => {
                if !out.is_empty() {
                    out.push('.');
                }
                out.push_str(name);
            }
        }
    }
    out
}

/// `value` as a Python object of the JSON data model.
pub(crate) fn to_python<'py, T: Serialize + ?Sized>(
    py: Python<'py>,
    value: &T,
) -> Result<Bound<'py, PyAny>> {
    value.serialize(Serializer { py, at: None })
}

#[derive(Clone, Copy)]
struct Serializer<'py, 'a> {
    py: Python<'py>,
    at: Option<&'a At<'a>>,
}

impl<'py> Serializer<'py, '_> {
    fn any<T>(self, v: T) -> Result<Bound<'py, PyAny>>
    where
        T: IntoPyObject<'py>,
    {
        Ok(v.into_bound_py_any(self.py)?)
    }

    fn float(self, v: f64) -> Result<Bound<'py, PyAny>> {
        if !v.is_finite() {
            return Err(ToPythonError::NonFinite {
                at: path(self.at),
                value: v,
            });
        }
        self.any(v)
    }

    /// `{variant: value}`.
    fn tagged(self, variant: &'static str, value: Bound<'py, PyAny>) -> Result<Bound<'py, PyAny>> {
        let d = PyDict::new(self.py);
        d.set_item(variant, value)?;
        Ok(d.into_any())
    }
}

/// A list being filled.
struct Seq<'py, 'a> {
    py: Python<'py>,
    at: Option<&'a At<'a>>,
    items: Vec<Bound<'py, PyAny>>,
    variant: Option<&'static str>,
}

impl<'py> Seq<'py, '_> {
    fn push<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<()> {
        let at = At {
            parent: self.at,
            key: Key::Index(self.items.len()),
        };
        let item = value.serialize(Serializer {
            py: self.py,
            at: Some(&at),
        })?;
        self.items.push(item);
        Ok(())
    }

    fn done(self) -> Result<Bound<'py, PyAny>> {
        let list = PyList::new(self.py, self.items)?.into_any();
        match self.variant {
            Some(v) => Serializer {
                py: self.py,
                at: self.at,
            }
            .tagged(v, list),
            None => Ok(list),
        }
    }
}

/// A dict being filled.
struct Map<'py, 'a> {
    py: Python<'py>,
    at: Option<&'a At<'a>>,
    dict: Bound<'py, PyDict>,
    key: Option<Bound<'py, PyAny>>,
    variant: Option<&'static str>,
}

impl<'py> Map<'py, '_> {
    fn field<T: Serialize + ?Sized>(&mut self, key: &'static str, value: &T) -> Result<()> {
        let at = At {
            parent: self.at,
            key: Key::Field(key),
        };
        let v = value.serialize(Serializer {
            py: self.py,
            at: Some(&at),
        })?;
        self.dict.set_item(key, v)?;
        Ok(())
    }

    fn done(self) -> Result<Bound<'py, PyAny>> {
        let dict = self.dict.into_any();
        match self.variant {
            Some(v) => Serializer {
                py: self.py,
                at: self.at,
            }
            .tagged(v, dict),
            None => Ok(dict),
        }
    }
}

impl<'py, 'a> ser::Serializer for Serializer<'py, 'a> {
    type Ok = Bound<'py, PyAny>;
    type Error = ToPythonError;
    type SerializeSeq = Seq<'py, 'a>;
    type SerializeTuple = Seq<'py, 'a>;
    type SerializeTupleStruct = Seq<'py, 'a>;
    type SerializeTupleVariant = Seq<'py, 'a>;
    type SerializeMap = Map<'py, 'a>;
    type SerializeStruct = Map<'py, 'a>;
    type SerializeStructVariant = Map<'py, 'a>;

    fn serialize_bool(self, v: bool) -> Result<Self::Ok> {
        self.any(v)
    }
    fn serialize_i8(self, v: i8) -> Result<Self::Ok> {
        self.any(v)
    }
    fn serialize_i16(self, v: i16) -> Result<Self::Ok> {
        self.any(v)
    }
    fn serialize_i32(self, v: i32) -> Result<Self::Ok> {
        self.any(v)
    }
    fn serialize_i64(self, v: i64) -> Result<Self::Ok> {
        self.any(v)
    }
    fn serialize_i128(self, v: i128) -> Result<Self::Ok> {
        self.any(v)
    }
    fn serialize_u8(self, v: u8) -> Result<Self::Ok> {
        self.any(v)
    }
    fn serialize_u16(self, v: u16) -> Result<Self::Ok> {
        self.any(v)
    }
    fn serialize_u32(self, v: u32) -> Result<Self::Ok> {
        self.any(v)
    }
    fn serialize_u64(self, v: u64) -> Result<Self::Ok> {
        self.any(v)
    }
    fn serialize_u128(self, v: u128) -> Result<Self::Ok> {
        self.any(v)
    }
    fn serialize_f32(self, v: f32) -> Result<Self::Ok> {
        self.float(f64::from(v))
    }
    fn serialize_f64(self, v: f64) -> Result<Self::Ok> {
        self.float(v)
    }
    fn serialize_char(self, v: char) -> Result<Self::Ok> {
        self.any(v.to_string())
    }
    fn serialize_str(self, v: &str) -> Result<Self::Ok> {
        Ok(PyString::new(self.py, v).into_any())
    }
    fn serialize_bytes(self, v: &[u8]) -> Result<Self::Ok> {
        // as serde_json: a list of numbers
        Ok(PyList::new(self.py, v)?.into_any())
    }
    fn serialize_none(self) -> Result<Self::Ok> {
        Ok(self.py.None().into_bound(self.py))
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<Self::Ok> {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Result<Self::Ok> {
        self.serialize_none()
    }
    fn serialize_unit_struct(self, _name: &'static str) -> Result<Self::Ok> {
        self.serialize_none()
    }
    fn serialize_unit_variant(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
    ) -> Result<Self::Ok> {
        self.serialize_str(variant)
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        value: &T,
    ) -> Result<Self::Ok> {
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
        value: &T,
    ) -> Result<Self::Ok> {
        let at = At {
            parent: self.at,
            key: Key::Field(variant),
        };
        let inner = value.serialize(Serializer {
            py: self.py,
            at: Some(&at),
        })?;
        self.tagged(variant, inner)
    }
    fn serialize_seq(self, len: Option<usize>) -> Result<Self::SerializeSeq> {
        Ok(Seq {
            py: self.py,
            at: self.at,
            items: Vec::with_capacity(len.unwrap_or(0)),
            variant: None,
        })
    }
    fn serialize_tuple(self, len: usize) -> Result<Self::SerializeTuple> {
        self.serialize_seq(Some(len))
    }
    fn serialize_tuple_struct(
        self,
        _name: &'static str,
        len: usize,
    ) -> Result<Self::SerializeTupleStruct> {
        self.serialize_seq(Some(len))
    }
    fn serialize_tuple_variant(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
        len: usize,
    ) -> Result<Self::SerializeTupleVariant> {
        Ok(Seq {
            variant: Some(variant),
            ..self.serialize_seq(Some(len))?
        })
    }
    fn serialize_map(self, _len: Option<usize>) -> Result<Self::SerializeMap> {
        Ok(Map {
            py: self.py,
            at: self.at,
            dict: PyDict::new(self.py),
            key: None,
            variant: None,
        })
    }
    fn serialize_struct(self, _name: &'static str, len: usize) -> Result<Self::SerializeStruct> {
        self.serialize_map(Some(len))
    }
    fn serialize_struct_variant(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
        len: usize,
    ) -> Result<Self::SerializeStructVariant> {
        Ok(Map {
            variant: Some(variant),
            ..self.serialize_map(Some(len))?
        })
    }
}

/// The four sequence-like compounds: each element pushed in turn, a list at the end (under
/// its name for a tuple variant).
macro_rules! elements {
    ($($compound:ident::$method:ident;)*) => {$(
        impl<'py> ser::$compound for Seq<'py, '_> {
            type Ok = Bound<'py, PyAny>;
            type Error = ToPythonError;
            fn $method<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<()> {
                self.push(value)
            }
            fn end(self) -> Result<Self::Ok> {
                self.done()
            }
        }
    )*};
}

elements! {
    SerializeSeq::serialize_element;
    SerializeTuple::serialize_element;
    SerializeTupleStruct::serialize_field;
    SerializeTupleVariant::serialize_field;
}

impl<'py> ser::SerializeMap for Map<'py, '_> {
    type Ok = Bound<'py, PyAny>;
    type Error = ToPythonError;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<()> {
        let k = key.serialize(Serializer {
            py: self.py,
            at: self.at,
        })?;
        // JSON's keys are text: a number or a name as its text
        let k = if k.is_instance_of::<PyString>() {
            k
        } else {
            k.str()?.into_any()
        };
        self.key = Some(k);
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<()> {
        let key = self
            .key
            .take()
            .ok_or_else(|| ToPythonError::Custom("a map value without its key".into()))?;
        let name = key.extract::<String>().unwrap_or_default();
        let at = At {
            parent: self.at,
            key: Key::Name(&name),
        };
        let v = value.serialize(Serializer {
            py: self.py,
            at: Some(&at),
        })?;
        self.dict.set_item(key, v)?;
        Ok(())
    }
    fn end(self) -> Result<Self::Ok> {
        self.done()
    }
}

impl<'py> ser::SerializeStruct for Map<'py, '_> {
    type Ok = Bound<'py, PyAny>;
    type Error = ToPythonError;
    fn serialize_field<T: Serialize + ?Sized>(
        &mut self,
        key: &'static str,
        value: &T,
    ) -> Result<()> {
        self.field(key, value)
    }
    fn end(self) -> Result<Self::Ok> {
        self.done()
    }
}

impl<'py> ser::SerializeStructVariant for Map<'py, '_> {
    type Ok = Bound<'py, PyAny>;
    type Error = ToPythonError;
    fn serialize_field<T: Serialize + ?Sized>(
        &mut self,
        key: &'static str,
        value: &T,
    ) -> Result<()> {
        self.field(key, value)
    }
    fn end(self) -> Result<Self::Ok> {
        self.done()
    }
}

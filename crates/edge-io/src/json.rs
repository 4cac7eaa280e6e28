//! JSON output that refuses non-finite numbers.
//!
//! serde_json writes NaN and ±∞ as `null`, which a reader cannot tell from "not applicable"
//! (`Option::None`). [`check_finite`] walks any `Serialize` value and names the path of the
//! first `f64`/`f32` that is not finite; [`to_json_pretty`] runs it before serializing, so no
//! results file or `--json` output of the workspace holds a `null` standing for a number.

use std::fmt::{self, Display};

use serde::Serialize;
use serde::ser::{self, Impossible};

/// A number that is not finite, found by [`check_finite`] at `path`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("`{path}` is not finite ({value}); JSON would write it as null")]
pub struct NonFiniteValue {
    /// Where, in the value tree: `phases[0].delta_k2.sigma_rad_s_g2` (`$` for the root).
    pub path: String,
    /// The value (NaN or ±∞).
    pub value: f64,
}

/// Errors of [`to_json_pretty`].
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum JsonError {
    /// A number in the value is not finite.
    #[error(transparent)]
    NonFinite(#[from] NonFiniteValue),
    /// serde_json refused the value (e.g. a map with non-string keys).
    #[error("cannot serialize to JSON")]
    Serialize(#[source] serde_json::Error),
}

impl JsonError {
    /// The error a caller reports for this one: `non_finite(path, value)` for a number that
    /// is not finite (its path in the value tree and the value), `other(message)` for
    /// serde_json's refusal, with its message.
    ///
    /// ```
    /// let e = edge_io::to_json_pretty(&[1.0, f64::INFINITY]).unwrap_err();
    /// let said = e.into_error(|path, value| format!("{path}: {value}"), |m| m);
    /// assert_eq!(said, "[1]: inf");
    /// ```
    pub fn into_error<E>(
        self,
        non_finite: impl FnOnce(String, f64) -> E,
        other: impl FnOnce(String) -> E,
    ) -> E {
        match self {
            Self::NonFinite(NonFiniteValue { path, value }) => non_finite(path, value),
            other_error @ Self::Serialize(_) => other(other_error.to_string()),
        }
    }
}

/// `Ok` when every floating-point number in `value` is finite; otherwise the path of the first
/// that is not. `None` (JSON `null` for "not applicable") is not a number and passes.
///
/// ```
/// #[derive(serde::Serialize)]
/// struct Phase { name: String, delta_k2: Option<f64>, residuals: Vec<f64> }
/// let ok = Phase { name: "pre".into(), delta_k2: None, residuals: vec![1e-300, 2.0] };
/// assert!(edge_io::check_finite(&ok).is_ok());
/// let bad = Phase { name: "pre".into(), delta_k2: None, residuals: vec![1.0, f64::NAN] };
/// assert_eq!(edge_io::check_finite(&bad).unwrap_err().path, "residuals[1]");
/// ```
///
/// # Errors
/// [`NonFiniteValue`] naming the first non-finite number's path.
pub fn check_finite<T: Serialize + ?Sized>(value: &T) -> Result<(), NonFiniteValue> {
    let mut path = Vec::new();
    match value.serialize(Walker { path: &mut path }) {
        Ok(()) => Ok(()),
        Err(Found::NonFinite(found)) => Err(found),
        // A value whose `Serialize` fails is serde_json's to report.
        Err(Found::Custom(_)) => Ok(()),
    }
}

/// `serde_json::to_string_pretty` after [`check_finite`]: the one JSON writer of the
/// workspace's result files.
///
/// # Errors
/// [`JsonError::NonFinite`] for a non-finite number, [`JsonError::Serialize`] when serde_json
/// refuses the value.
pub fn to_json_pretty<T: Serialize + ?Sized>(value: &T) -> Result<String, JsonError> {
    check_finite(value)?;
    serde_json::to_string_pretty(value).map_err(JsonError::Serialize)
}

/// One step of a path into the value tree.
#[derive(Debug, Clone)]
enum Step {
    Field(String),
    Index(usize),
}

fn render(path: &[Step]) -> String {
    if path.is_empty() {
        return "$".to_string();
    }
    let mut out = String::new();
    for step in path {
        match step {
            Step::Field(name) => {
                if !out.is_empty() {
                    out.push('.');
                }
                out.push_str(name);
            }
            Step::Index(i) => {
                out.push('[');
                out.push_str(&i.to_string());
                out.push(']');
            }
        }
    }
    out
}

/// The walker's "error": either the finding, or an error raised by a `Serialize` impl.
#[derive(Debug)]
enum Found {
    NonFinite(NonFiniteValue),
    Custom(String),
}

impl Display for Found {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite(e) => e.fmt(f),
            Self::Custom(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for Found {}

impl ser::Error for Found {
    fn custom<T: Display>(msg: T) -> Self {
        Self::Custom(msg.to_string())
    }
}

struct Walker<'a> {
    path: &'a mut Vec<Step>,
}

impl Walker<'_> {
    fn float(self, value: f64) -> Result<(), Found> {
        if value.is_finite() {
            Ok(())
        } else {
            Err(Found::NonFinite(NonFiniteValue {
                path: render(self.path),
                value,
            }))
        }
    }

    fn nested<T: Serialize + ?Sized>(&mut self, step: Step, value: &T) -> Result<(), Found> {
        self.path.push(step);
        let result = value.serialize(Walker {
            path: &mut *self.path,
        });
        self.path.pop();
        result
    }
}

/// Walks a sequence, tuple, map or struct, counting elements.
struct Compound<'a> {
    walker: Walker<'a>,
    index: usize,
    key: Option<String>,
}

impl<'a> Compound<'a> {
    fn new(walker: Walker<'a>) -> Self {
        Self {
            walker,
            index: 0,
            key: None,
        }
    }

    /// A variant's compound: its fields under the step of its name, which its `end` leaves.
    fn variant(walker: Walker<'a>, variant: &'static str) -> Self {
        walker.path.push(Step::Field(variant.to_string()));
        Self::new(walker)
    }

    fn element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Found> {
        let step = Step::Index(self.index);
        self.index += 1;
        self.walker.nested(step, value)
    }
}

macro_rules! ok_scalars {
    ($($method:ident($ty:ty)),* $(,)?) => {
        $(fn $method(self, _: $ty) -> Result<(), Found> { Ok(()) })*
    };
}

impl<'a> ser::Serializer for Walker<'a> {
    type Ok = ();
    type Error = Found;
    type SerializeSeq = Compound<'a>;
    type SerializeTuple = Compound<'a>;
    type SerializeTupleStruct = Compound<'a>;
    type SerializeTupleVariant = Compound<'a>;
    type SerializeMap = Compound<'a>;
    type SerializeStruct = Compound<'a>;
    type SerializeStructVariant = Compound<'a>;

    ok_scalars!(
        serialize_bool(bool),
        serialize_i8(i8),
        serialize_i16(i16),
        serialize_i32(i32),
        serialize_i64(i64),
        serialize_i128(i128),
        serialize_u8(u8),
        serialize_u16(u16),
        serialize_u32(u32),
        serialize_u64(u64),
        serialize_u128(u128),
        serialize_char(char),
        serialize_str(&str),
        serialize_bytes(&[u8]),
    );

    fn serialize_f32(self, v: f32) -> Result<(), Found> {
        self.float(f64::from(v))
    }
    fn serialize_f64(self, v: f64) -> Result<(), Found> {
        self.float(v)
    }
    fn serialize_none(self) -> Result<(), Found> {
        Ok(())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<(), Found> {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Result<(), Found> {
        Ok(())
    }
    fn serialize_unit_struct(self, _: &'static str) -> Result<(), Found> {
        Ok(())
    }
    fn serialize_unit_variant(self, _: &'static str, _: u32, _: &'static str) -> Result<(), Found> {
        Ok(())
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        value: &T,
    ) -> Result<(), Found> {
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        mut self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        value: &T,
    ) -> Result<(), Found> {
        self.nested(Step::Field(variant.to_string()), value)
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Compound<'a>, Found> {
        Ok(Compound::new(self))
    }
    fn serialize_tuple(self, _: usize) -> Result<Compound<'a>, Found> {
        Ok(Compound::new(self))
    }
    fn serialize_tuple_struct(self, _: &'static str, _: usize) -> Result<Compound<'a>, Found> {
        Ok(Compound::new(self))
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        _: usize,
    ) -> Result<Compound<'a>, Found> {
        Ok(Compound::variant(self, variant))
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Compound<'a>, Found> {
        Ok(Compound::new(self))
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Compound<'a>, Found> {
        Ok(Compound::new(self))
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        _: usize,
    ) -> Result<Compound<'a>, Found> {
        Ok(Compound::variant(self, variant))
    }
}

/// The four sequence-like compounds: each element walked under its index; `pop` for a
/// variant, whose end leaves the step of its name that `serialize_tuple_variant` entered.
macro_rules! elements {
    ($($compound:ident::$method:ident, pop: $pop:literal;)*) => {$(
        impl ser::$compound for Compound<'_> {
            type Ok = ();
            type Error = Found;
            fn $method<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Found> {
                self.element(value)
            }
            fn end(self) -> Result<(), Found> {
                if $pop {
                    self.walker.path.pop();
                }
                Ok(())
            }
        }
    )*};
}

elements! {
    SerializeSeq::serialize_element, pop: false;
    SerializeTuple::serialize_element, pop: false;
    SerializeTupleStruct::serialize_field, pop: false;
    SerializeTupleVariant::serialize_field, pop: true;
}

impl ser::SerializeMap for Compound<'_> {
    type Ok = ();
    type Error = Found;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), Found> {
        self.key = Some(key.serialize(KeyName).unwrap_or_else(|_| "?".to_string()));
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Found> {
        let key = self.key.take().unwrap_or_else(|| "?".to_string());
        self.walker.nested(Step::Field(key), value)
    }
    fn end(self) -> Result<(), Found> {
        Ok(())
    }
}

impl ser::SerializeStruct for Compound<'_> {
    type Ok = ();
    type Error = Found;
    fn serialize_field<T: Serialize + ?Sized>(
        &mut self,
        name: &'static str,
        value: &T,
    ) -> Result<(), Found> {
        self.walker.nested(Step::Field(name.to_string()), value)
    }
    fn end(self) -> Result<(), Found> {
        Ok(())
    }
}

impl ser::SerializeStructVariant for Compound<'_> {
    type Ok = ();
    type Error = Found;
    fn serialize_field<T: Serialize + ?Sized>(
        &mut self,
        name: &'static str,
        value: &T,
    ) -> Result<(), Found> {
        self.walker.nested(Step::Field(name.to_string()), value)
    }
    fn end(self) -> Result<(), Found> {
        self.walker.path.pop();
        Ok(())
    }
}

/// A map key as text, for the path (`?` for keys that are not strings or numbers).
struct KeyName;

macro_rules! key_to_string {
    ($($method:ident($ty:ty)),* $(,)?) => {
        $(fn $method(self, v: $ty) -> Result<String, Found> { Ok(v.to_string()) })*
    };
}

macro_rules! key_refused {
    ($($method:ident($($ty:ty),*)),* $(,)?) => {
        $(fn $method(self, $(_: $ty),*) -> Result<String, Found> {
            Err(Found::Custom(String::new()))
        })*
    };
}

impl ser::Serializer for KeyName {
    type Ok = String;
    type Error = Found;
    type SerializeSeq = Impossible<String, Found>;
    type SerializeTuple = Impossible<String, Found>;
    type SerializeTupleStruct = Impossible<String, Found>;
    type SerializeTupleVariant = Impossible<String, Found>;
    type SerializeMap = Impossible<String, Found>;
    type SerializeStruct = Impossible<String, Found>;
    type SerializeStructVariant = Impossible<String, Found>;

    key_to_string!(
        serialize_bool(bool),
        serialize_i8(i8),
        serialize_i16(i16),
        serialize_i32(i32),
        serialize_i64(i64),
        serialize_i128(i128),
        serialize_u8(u8),
        serialize_u16(u16),
        serialize_u32(u32),
        serialize_u64(u64),
        serialize_u128(u128),
        serialize_f32(f32),
        serialize_f64(f64),
        serialize_char(char),
        serialize_str(&str),
    );
    key_refused!(
        serialize_bytes(&[u8]),
        serialize_none(),
        serialize_unit(),
        serialize_unit_struct(&'static str),
    );

    fn serialize_unit_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
    ) -> Result<String, Found> {
        Ok(variant.to_string())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<String, Found> {
        value.serialize(self)
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        value: &T,
    ) -> Result<String, Found> {
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: &T,
    ) -> Result<String, Found> {
        Err(Found::Custom(String::new()))
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Self::SerializeSeq, Found> {
        Err(Found::Custom(String::new()))
    }
    fn serialize_tuple(self, _: usize) -> Result<Self::SerializeTuple, Found> {
        Err(Found::Custom(String::new()))
    }
    fn serialize_tuple_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleStruct, Found> {
        Err(Found::Custom(String::new()))
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleVariant, Found> {
        Err(Found::Custom(String::new()))
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Self::SerializeMap, Found> {
        Err(Found::Custom(String::new()))
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Self::SerializeStruct, Found> {
        Err(Found::Custom(String::new()))
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeStructVariant, Found> {
        Err(Found::Custom(String::new()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;

    #[derive(Serialize)]
    enum Shape {
        Point { x: f64 },
        Pair(f64, f64),
        Wrapped(Vec<f64>),
    }

    #[derive(Serialize)]
    struct Tree {
        name: &'static str,
        none: Option<f64>,
        shapes: Vec<Shape>,
        table: BTreeMap<String, (u32, f64)>,
    }

    fn tree() -> Tree {
        Tree {
            name: "t",
            none: None,
            shapes: vec![
                Shape::Point { x: 1.0 },
                Shape::Pair(2.0, 3.0),
                Shape::Wrapped(vec![4.0, 5.0]),
            ],
            table: BTreeMap::from([("k".to_string(), (1, 6.0))]),
        }
    }

    #[test]
    fn finite_tree_passes_and_none_is_not_a_number() {
        assert_eq!(check_finite(&tree()), Ok(()));
        let json = to_json_pretty(&tree()).unwrap();
        assert!(json.contains("\"none\": null"), "{json}");
    }

    #[test]
    fn every_position_is_named() {
        type Spoil = fn(&mut Tree);
        let cases: [(Spoil, &str); 4] = [
            (
                |t| t.shapes[0] = Shape::Point { x: f64::NAN },
                "shapes[0].Point.x",
            ),
            (
                |t| t.shapes[1] = Shape::Pair(2.0, f64::INFINITY),
                "shapes[1].Pair[1]",
            ),
            (
                |t| t.shapes[2] = Shape::Wrapped(vec![0.0, 1.0, f64::NEG_INFINITY]),
                "shapes[2].Wrapped[2]",
            ),
            (|t| t.none = Some(f64::NAN), "none"),
        ];
        for (spoil, path) in cases {
            let mut t = tree();
            spoil(&mut t);
            assert_eq!(check_finite(&t).unwrap_err().path, path);
            assert!(matches!(to_json_pretty(&t), Err(JsonError::NonFinite(_))));
        }
        let mut t = tree();
        t.table.insert("gain".to_string(), (2, f64::NAN));
        assert_eq!(check_finite(&t).unwrap_err().path, "table.gain[1]");
        assert_eq!(check_finite(&f64::NAN).unwrap_err().path, "$");
        assert!(check_finite(&f32::INFINITY).is_err());
    }
}

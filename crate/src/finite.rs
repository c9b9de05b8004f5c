//! The last guard before a file or a screen: every number in a result is finite.
//!
//! serde_json writes a NaN or an infinity as `null`, silently, and the page would draw
//! it as a gap or "NaN". The inputs' domain ([`crate::domain`]) and the surrogates' guard
//! keep results finite; [`check`] makes sure of it where a result leaves the core (the
//! CLI's JSON and CSV, the page's results): it walks any serialisable value and names the
//! path of the first number that is not finite. Hand-written rather than a crate
//! (serde-value and the like build a copy of the whole tree): it allocates only the keys
//! of maps on its path, and writes the path out only when it names one.

use crate::error::{Result, RideError};
use serde::ser::{self, Serialize};
use std::fmt;

/// Checks that every `f32`/`f64` in `value` is finite; the error names the path of the
/// first one that is not (`front[3].bacc`).
pub fn check<T: Serialize + ?Sized>(value: &T) -> Result<()> {
    let mut c = Checker { path: Vec::new() };
    value.serialize(&mut c).map_err(|e| {
        RideError::Numerical(format!(
            "internal: a result holds a number that is not finite at `{}`; nothing was written (please report this with the command or page state)",
            e.0
        ))
    })
}

/// The path of the first non-finite number (the error type of the walk).
#[derive(Debug)]
struct Found(String);

impl fmt::Display for Found {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Found {}

impl ser::Error for Found {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        Found(format!("<{msg}>"))
    }
}

/// One step of the path: a struct field or enum variant, a sequence index, or a map key.
enum Step {
    Name(&'static str),
    Index(usize),
    Key(String),
}

struct Checker {
    path: Vec<Step>,
}

impl Checker {
    fn found(&self) -> Found {
        let mut s = String::new();
        for p in &self.path {
            let name = match p {
                Step::Index(i) => {
                    s += &format!("[{i}]");
                    continue;
                }
                Step::Name(n) => n,
                Step::Key(k) => k.as_str(),
            };
            if !s.is_empty() {
                s.push('.');
            }
            s += name;
        }
        Found(if s.is_empty() { ".".into() } else { s })
    }

    fn float(&self, v: f64) -> std::result::Result<(), Found> {
        if v.is_finite() {
            Ok(())
        } else {
            Err(self.found())
        }
    }

    fn at<T: Serialize + ?Sized>(&mut self, key: Step, v: &T) -> std::result::Result<(), Found> {
        self.path.push(key);
        let r = v.serialize(&mut *self);
        self.path.pop();
        r
    }
}

type R = std::result::Result<(), Found>;

impl<'a> ser::Serializer for &'a mut Checker {
    type Ok = ();
    type Error = Found;
    type SerializeSeq = Seq<'a>;
    type SerializeTuple = Seq<'a>;
    type SerializeTupleStruct = Seq<'a>;
    type SerializeTupleVariant = Seq<'a>;
    type SerializeMap = Map<'a>;
    type SerializeStruct = Map<'a>;
    type SerializeStructVariant = Map<'a>;

    fn serialize_bool(self, _: bool) -> R {
        Ok(())
    }
    fn serialize_i8(self, _: i8) -> R {
        Ok(())
    }
    fn serialize_i16(self, _: i16) -> R {
        Ok(())
    }
    fn serialize_i32(self, _: i32) -> R {
        Ok(())
    }
    fn serialize_i64(self, _: i64) -> R {
        Ok(())
    }
    fn serialize_u8(self, _: u8) -> R {
        Ok(())
    }
    fn serialize_u16(self, _: u16) -> R {
        Ok(())
    }
    fn serialize_u32(self, _: u32) -> R {
        Ok(())
    }
    fn serialize_u64(self, _: u64) -> R {
        Ok(())
    }
    fn serialize_f32(self, v: f32) -> R {
        self.float(v as f64)
    }
    fn serialize_f64(self, v: f64) -> R {
        self.float(v)
    }
    fn serialize_char(self, _: char) -> R {
        Ok(())
    }
    fn serialize_str(self, _: &str) -> R {
        Ok(())
    }
    fn serialize_bytes(self, _: &[u8]) -> R {
        Ok(())
    }
    fn serialize_none(self) -> R {
        Ok(())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, v: &T) -> R {
        v.serialize(self)
    }
    fn serialize_unit(self) -> R {
        Ok(())
    }
    fn serialize_unit_struct(self, _: &'static str) -> R {
        Ok(())
    }
    fn serialize_unit_variant(self, _: &'static str, _: u32, _: &'static str) -> R {
        Ok(())
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(self, _: &'static str, v: &T) -> R {
        v.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        v: &T,
    ) -> R {
        self.at(Step::Name(variant), v)
    }
    fn serialize_seq(self, _: Option<usize>) -> std::result::Result<Seq<'a>, Found> {
        Ok(Seq::new(self))
    }
    fn serialize_tuple(self, _: usize) -> std::result::Result<Seq<'a>, Found> {
        Ok(Seq::new(self))
    }
    fn serialize_tuple_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> std::result::Result<Seq<'a>, Found> {
        Ok(Seq::new(self))
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> std::result::Result<Seq<'a>, Found> {
        Ok(Seq::new(self))
    }
    fn serialize_map(self, _: Option<usize>) -> std::result::Result<Map<'a>, Found> {
        Ok(Map::new(self))
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> std::result::Result<Map<'a>, Found> {
        Ok(Map::new(self))
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> std::result::Result<Map<'a>, Found> {
        Ok(Map::new(self))
    }
}

/// A sequence being walked: the checker and the next index.
struct Seq<'a> {
    c: &'a mut Checker,
    index: usize,
}

/// A map or struct being walked: the checker and the pending key.
struct Map<'a> {
    c: &'a mut Checker,
    key: String,
}

impl<'a> Seq<'a> {
    fn new(c: &'a mut Checker) -> Seq<'a> {
        Seq { c, index: 0 }
    }
}

impl<'a> Map<'a> {
    fn new(c: &'a mut Checker) -> Map<'a> {
        Map {
            c,
            key: String::new(),
        }
    }
}

impl Seq<'_> {
    fn element<T: Serialize + ?Sized>(&mut self, v: &T) -> R {
        let key = Step::Index(self.index);
        self.index += 1;
        self.c.at(key, v)
    }
}

impl ser::SerializeSeq for Seq<'_> {
    type Ok = ();
    type Error = Found;
    fn serialize_element<T: Serialize + ?Sized>(&mut self, v: &T) -> R {
        self.element(v)
    }
    fn end(self) -> R {
        Ok(())
    }
}

impl ser::SerializeTuple for Seq<'_> {
    type Ok = ();
    type Error = Found;
    fn serialize_element<T: Serialize + ?Sized>(&mut self, v: &T) -> R {
        self.element(v)
    }
    fn end(self) -> R {
        Ok(())
    }
}

impl ser::SerializeTupleStruct for Seq<'_> {
    type Ok = ();
    type Error = Found;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, v: &T) -> R {
        self.element(v)
    }
    fn end(self) -> R {
        Ok(())
    }
}

impl ser::SerializeTupleVariant for Seq<'_> {
    type Ok = ();
    type Error = Found;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, v: &T) -> R {
        self.element(v)
    }
    fn end(self) -> R {
        Ok(())
    }
}

/// A map key as text (string and number keys; anything else by its position).
struct KeyText(String);

impl ser::Serializer for &mut KeyText {
    type Ok = ();
    type Error = Found;
    type SerializeSeq = ser::Impossible<(), Found>;
    type SerializeTuple = ser::Impossible<(), Found>;
    type SerializeTupleStruct = ser::Impossible<(), Found>;
    type SerializeTupleVariant = ser::Impossible<(), Found>;
    type SerializeMap = ser::Impossible<(), Found>;
    type SerializeStruct = ser::Impossible<(), Found>;
    type SerializeStructVariant = ser::Impossible<(), Found>;
    fn serialize_bool(self, v: bool) -> R {
        self.0 = v.to_string();
        Ok(())
    }
    fn serialize_i8(self, v: i8) -> R {
        self.serialize_i64(v as i64)
    }
    fn serialize_i16(self, v: i16) -> R {
        self.serialize_i64(v as i64)
    }
    fn serialize_i32(self, v: i32) -> R {
        self.serialize_i64(v as i64)
    }
    fn serialize_i64(self, v: i64) -> R {
        self.0 = v.to_string();
        Ok(())
    }
    fn serialize_u8(self, v: u8) -> R {
        self.serialize_u64(v as u64)
    }
    fn serialize_u16(self, v: u16) -> R {
        self.serialize_u64(v as u64)
    }
    fn serialize_u32(self, v: u32) -> R {
        self.serialize_u64(v as u64)
    }
    fn serialize_u64(self, v: u64) -> R {
        self.0 = v.to_string();
        Ok(())
    }
    fn serialize_f32(self, v: f32) -> R {
        self.serialize_f64(v as f64)
    }
    fn serialize_f64(self, v: f64) -> R {
        self.0 = v.to_string();
        Ok(())
    }
    fn serialize_char(self, v: char) -> R {
        self.0 = v.to_string();
        Ok(())
    }
    fn serialize_str(self, v: &str) -> R {
        self.0 = v.to_string();
        Ok(())
    }
    fn serialize_bytes(self, _: &[u8]) -> R {
        Ok(())
    }
    fn serialize_none(self) -> R {
        Ok(())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, v: &T) -> R {
        v.serialize(self)
    }
    fn serialize_unit(self) -> R {
        Ok(())
    }
    fn serialize_unit_struct(self, _: &'static str) -> R {
        Ok(())
    }
    fn serialize_unit_variant(self, _: &'static str, _: u32, v: &'static str) -> R {
        self.0 = v.to_string();
        Ok(())
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(self, _: &'static str, v: &T) -> R {
        v.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: &T,
    ) -> R {
        Ok(())
    }
    fn serialize_seq(self, _: Option<usize>) -> std::result::Result<Self::SerializeSeq, Found> {
        Err(Found("<key>".into()))
    }
    fn serialize_tuple(self, _: usize) -> std::result::Result<Self::SerializeTuple, Found> {
        Err(Found("<key>".into()))
    }
    fn serialize_tuple_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> std::result::Result<Self::SerializeTupleStruct, Found> {
        Err(Found("<key>".into()))
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> std::result::Result<Self::SerializeTupleVariant, Found> {
        Err(Found("<key>".into()))
    }
    fn serialize_map(self, _: Option<usize>) -> std::result::Result<Self::SerializeMap, Found> {
        Err(Found("<key>".into()))
    }
    fn serialize_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> std::result::Result<Self::SerializeStruct, Found> {
        Err(Found("<key>".into()))
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> std::result::Result<Self::SerializeStructVariant, Found> {
        Err(Found("<key>".into()))
    }
}

impl ser::SerializeMap for Map<'_> {
    type Ok = ();
    type Error = Found;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, k: &T) -> R {
        let mut t = KeyText(String::new());
        // A key that is not text is named by nothing: the value's path still helps.
        let _ = k.serialize(&mut t);
        self.key = t.0;
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, v: &T) -> R {
        let key = std::mem::take(&mut self.key);
        self.c.at(Step::Key(key), v)
    }
    fn end(self) -> R {
        Ok(())
    }
}

impl ser::SerializeStruct for Map<'_> {
    type Ok = ();
    type Error = Found;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, key: &'static str, v: &T) -> R {
        self.c.at(Step::Name(key), v)
    }
    fn end(self) -> R {
        Ok(())
    }
}

impl ser::SerializeStructVariant for Map<'_> {
    type Ok = ();
    type Error = Found;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, key: &'static str, v: &T) -> R {
        self.c.at(Step::Name(key), v)
    }
    fn end(self) -> R {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Serialize;
    use std::collections::BTreeMap;

    #[derive(Serialize)]
    struct Point {
        ks: f64,
        bacc: f64,
    }

    #[derive(Serialize)]
    struct Report {
        name: String,
        front: Vec<Point>,
        extra: Option<[f64; 2]>,
        by: BTreeMap<String, f64>,
    }

    fn report(bad: Option<(usize, f64)>) -> Report {
        let mut front: Vec<Point> = (0..4)
            .map(|k| Point {
                ks: 1e4 + k as f64,
                bacc: 0.5,
            })
            .collect();
        if let Some((k, v)) = bad {
            front[k].bacc = v;
        }
        Report {
            name: "x".into(),
            front,
            extra: Some([1.0, 2.0]),
            by: BTreeMap::from([("dtl".to_string(), 300.0)]),
        }
    }

    #[test]
    fn finite_results_pass_and_the_first_bad_number_is_named_by_its_path() {
        assert!(check(&report(None)).is_ok());
        let e = check(&report(Some((3, f64::NAN)))).unwrap_err().to_string();
        assert!(e.contains("at `front[3].bacc`"), "{e}");
        let e = check(&report(Some((0, f64::NEG_INFINITY))))
            .unwrap_err()
            .to_string();
        assert!(e.contains("at `front[0].bacc`"), "{e}");
        let mut r = report(None);
        r.by.insert("sws".into(), f64::INFINITY);
        assert!(check(&r).unwrap_err().to_string().contains("at `by.sws`"));
        r.by.clear();
        r.extra = Some([1.0, f64::NAN]);
        assert!(check(&r).unwrap_err().to_string().contains("at `extra[1]`"));
        assert!(check(&f64::NAN).unwrap_err().to_string().contains("at `.`"));
    }
}

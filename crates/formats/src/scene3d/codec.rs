//! CDR: a message written field by field ([`CdrOut`]), and a JSON message encoded by its
//! type's table and decoded back.

use serde_json::{Value, json};

use crate::cdr::CDR_LE_HEADER;

use super::msg::{Msg, Ty};

/// A CDR message written field by field into a buffer, each type at its alignment
/// (counted past the 4-byte encapsulation header): the primitives of [`encode`], and of
/// the per-frame messages of the 3D view written without a JSON value first.
pub(super) struct CdrOut<'a>(pub(super) &'a mut Vec<u8>);

impl CdrOut<'_> {
    /// Start a message: clear the buffer, write the little-endian header.
    pub(super) fn start(buf: &mut Vec<u8>) -> CdrOut<'_> {
        buf.clear();
        buf.extend_from_slice(&CDR_LE_HEADER);
        CdrOut(buf)
    }

    pub(super) fn align(&mut self, n: usize) {
        align(self.0, n);
    }

    /// A `float64`; a value that is not finite is written as NaN, as a JSON `null` is.
    pub(super) fn f64(&mut self, x: f64) {
        self.align(8);
        let x = if x.is_finite() { x } else { f64::NAN };
        self.0.extend_from_slice(&x.to_le_bytes());
    }

    pub(super) fn u32(&mut self, x: u32) {
        self.align(4);
        self.0.extend_from_slice(&x.to_le_bytes());
    }

    pub(super) fn str(&mut self, text: &str) {
        self.u32(text.len() as u32 + 1);
        self.0.extend_from_slice(text.as_bytes());
        self.0.push(0);
    }

    /// A `builtin_interfaces/Time` of `ns` (as [`ros_time`](super::ros_time)).
    pub(super) fn time(&mut self, ns: u64) {
        self.u32((ns / 1_000_000_000) as i64 as i32 as u32);
        self.u32((ns % 1_000_000_000) as u32);
    }

    pub(super) fn xyz(&mut self, (x, y, z): (f64, f64, f64)) {
        self.f64(x);
        self.f64(y);
        self.f64(z);
    }

    pub(super) fn four(&mut self, v: [f64; 4]) {
        for x in v {
            self.f64(x);
        }
    }
}

/// Pad `buf` with zeros to a multiple of `n` past the 4-byte encapsulation header.
fn align(buf: &mut Vec<u8>, n: usize) {
    while (buf.len() - 4) % n != 0 {
        buf.push(0);
    }
}

/// `v` (a JSON object with `m`'s field names) as a CDR message of type `m`, into `buf`:
/// the little-endian header, then every field in definition order; a field `v` lacks is
/// zero, false, empty (a JSON `null` number is NaN).
pub fn encode(m: &Msg, v: &Value, buf: &mut Vec<u8>) {
    buf.clear();
    buf.extend_from_slice(&CDR_LE_HEADER);
    put_msg(m, v, buf);
}

fn put_msg(m: &Msg, v: &Value, buf: &mut Vec<u8>) {
    for (name, ty) in m.fields {
        put_field(ty, v.get(name), buf);
    }
}

fn put_field(ty: &Ty, v: Option<&Value>, buf: &mut Vec<u8>) {
    let int = |v: Option<&Value>| v.and_then(Value::as_i64).unwrap_or(0);
    let mut out = CdrOut(buf);
    match ty {
        // a JSON number is finite, and `null` is NaN: what `CdrOut::f64` writes
        Ty::F64 => out.f64(match v {
            Some(Value::Null) => f64::NAN,
            v => v.and_then(Value::as_f64).unwrap_or(0.0),
        }),
        Ty::U8 => out.0.push(int(v) as u8),
        Ty::Bool => out
            .0
            .push(u8::from(v.and_then(Value::as_bool).unwrap_or(false))),
        Ty::I32 => out.u32(int(v) as i32 as u32),
        Ty::U32 => out.u32(int(v) as u32),
        Ty::Str => out.str(v.and_then(Value::as_str).unwrap_or("")),
        Ty::Msg(m) => put_msg(m, v.unwrap_or(&Value::Null), buf),
        Ty::Seq(t) => {
            let items = v.and_then(Value::as_array).map_or(&[][..], Vec::as_slice);
            out.u32(items.len() as u32);
            for item in items {
                put_field(t, Some(item), buf);
            }
        }
    }
}

/// A CDR message of type `m` read back as JSON (field names as in the definition;
/// NaN as `null`); an error says where the bytes end or what is wrong.
pub fn decode(m: &Msg, data: &[u8]) -> Result<Value, String> {
    let Some(header) = data.get(..4) else {
        return Err(format!("{} bytes, shorter than the CDR header", data.len()));
    };
    if header[..2] != CDR_LE_HEADER[..2] {
        return Err("not little-endian plain CDR".into());
    }
    let mut r = Reader { data, at: 4 };
    let v = r.msg(m)?;
    match data.len() - r.at {
        0 => Ok(v),
        n => Err(format!("{n} bytes after the last field of {}", m.name)),
    }
}

struct Reader<'a> {
    data: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take(&mut self, align: usize, n: usize) -> Result<&[u8], String> {
        let start = 4 + (self.at - 4).next_multiple_of(align);
        let bytes = self
            .data
            .get(start..start + n)
            .ok_or_else(|| format!("message ends at byte {} inside a field", self.data.len()))?;
        self.at = start + n;
        Ok(bytes)
    }

    fn u32(&mut self) -> Result<u32, String> {
        let b = self.take(4, 4)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    fn msg(&mut self, m: &Msg) -> Result<Value, String> {
        let mut obj = serde_json::Map::with_capacity(m.fields.len());
        for (name, ty) in m.fields {
            obj.insert((*name).to_string(), self.field(ty)?);
        }
        Ok(Value::Object(obj))
    }

    fn field(&mut self, ty: &Ty) -> Result<Value, String> {
        Ok(match ty {
            Ty::F64 => {
                let b = self.take(8, 8)?;
                json!(f64::from_le_bytes(b.try_into().unwrap_or([0; 8])))
            }
            Ty::U8 => json!(self.take(1, 1)?[0]),
            Ty::Bool => match self.take(1, 1)?[0] {
                0 => json!(false),
                1 => json!(true),
                b => return Err(format!("bool byte {b}")),
            },
            Ty::I32 => json!(self.u32()? as i32),
            Ty::U32 => json!(self.u32()?),
            Ty::Str => {
                let n = self.u32()? as usize;
                let bytes = self.take(1, n)?;
                let (nul, text) = bytes.split_last().ok_or("a string of length 0")?;
                if *nul != 0 {
                    return Err("a string without its NUL".into());
                }
                json!(std::str::from_utf8(text).map_err(|e| e.to_string())?)
            }
            Ty::Msg(m) => self.msg(m)?,
            Ty::Seq(t) => {
                let n = self.u32()? as usize;
                // every element takes at least one byte: a count beyond the bytes left is damage
                if n > self.data.len() - self.at {
                    return Err(format!("a sequence of {n} in {} bytes", self.data.len()));
                }
                let mut items = Vec::with_capacity(n);
                for _ in 0..n {
                    items.push(self.field(t)?);
                }
                Value::Array(items)
            }
        })
    }
}

//! A NetCDF-3 writer (the "64-bit offset" variant of the classic format), for the results
//! table: one dimension `point`, one variable per column, attributes for units.
//!
//! Why NetCDF-3: it is a small, fully specified format (the NetCDF Users Guide, "File
//! Format Specification"; Unidata, netCDF 4.9, Appendix "The NetCDF Classic Format
//! Specification"), written here in ~150 lines without a C library or a large dependency;
//! xarray opens it directly (`xarray.open_dataset(path)`, scipy engine), as do
//! `scipy.io.netcdf_file`, netCDF4-python, R's ncdf4, MATLAB's `ncread` and ParaView.
//! Parquet would need a crate with a large compile-time cost (arrow), for a table of a few
//! thousand rows.
//!
//! Layout (every number big-endian):
//! ```text
//! "CDF" 0x02 | numrecs = 0 | NC_DIMENSION n (name, length)... | NC_ATTRIBUTE n (global
//! attributes) | NC_VARIABLE n (name, rank, dimids, attributes, type, vsize, begin: i64)...
//! | the variables' data, each padded to 4 bytes, in order
//! ```
//! Numbers are NC_DOUBLE (missing: NaN), counts NC_INT, text NC_CHAR arrays over a
//! per-variable string-length dimension, with the attribute `_Encoding = "utf-8"` by which
//! xarray decodes them to strings.

/// A column of the table.
#[derive(Debug, Clone, PartialEq)]
pub enum Column {
    /// 32-bit integers (NC_INT).
    Int(Vec<i32>),
    /// Doubles (NC_DOUBLE); NaN where missing.
    Double(Vec<f64>),
    /// Strings (NC_CHAR over a string-length dimension).
    Text(Vec<String>),
}

impl Column {
    fn len(&self) -> usize {
        match self {
            Column::Int(v) => v.len(),
            Column::Double(v) => v.len(),
            Column::Text(v) => v.len(),
        }
    }
}

/// An attribute value.
#[derive(Debug, Clone, PartialEq)]
pub enum Attr {
    /// Text (NC_CHAR).
    Text(String),
    /// A double (NC_DOUBLE).
    Double(f64),
}

/// A variable: a name, its attributes and its column.
#[derive(Debug, Clone, PartialEq)]
pub struct Variable {
    /// The name (any UTF-8 without '/' or control characters).
    pub name: String,
    /// Its attributes (`units`, `long_name`, ...).
    pub attrs: Vec<(String, Attr)>,
    /// The data, one value per point.
    pub data: Column,
}

const NC_DIMENSION: u32 = 0x0A;
const NC_VARIABLE: u32 = 0x0B;
const NC_ATTRIBUTE: u32 = 0x0C;
const NC_CHAR: u32 = 2;
const NC_INT: u32 = 4;
const NC_DOUBLE: u32 = 6;

fn pad4(b: &mut Vec<u8>) {
    while !b.len().is_multiple_of(4) {
        b.push(0);
    }
}

fn u32be(b: &mut Vec<u8>, x: u32) {
    b.extend_from_slice(&x.to_be_bytes());
}

fn name(b: &mut Vec<u8>, s: &str) {
    u32be(b, s.len() as u32);
    b.extend_from_slice(s.as_bytes());
    pad4(b);
}

fn attrs(b: &mut Vec<u8>, list: &[(String, Attr)]) {
    if list.is_empty() {
        b.extend_from_slice(&[0; 8]);
        return;
    }
    u32be(b, NC_ATTRIBUTE);
    u32be(b, list.len() as u32);
    for (n, a) in list {
        name(b, n);
        match a {
            Attr::Text(t) => {
                u32be(b, NC_CHAR);
                u32be(b, t.len() as u32);
                b.extend_from_slice(t.as_bytes());
                pad4(b);
            }
            Attr::Double(x) => {
                u32be(b, NC_DOUBLE);
                u32be(b, 1);
                b.extend_from_slice(&x.to_be_bytes());
            }
        }
    }
}

/// A text column's string length: its longest value in bytes (at least 1).
fn strlen(v: &[String]) -> usize {
    v.iter().map(String::len).max().unwrap_or(0).max(1)
}

/// The file's bytes: the dimension `point` of length `n`, a string-length dimension
/// `<name>_strlen` per text variable, the global attributes and the variables. Fails (with
/// the reason) where a column's length is not `n` or the file would exceed the format's
/// limits.
pub fn write(n: usize, globals: &[(String, Attr)], vars: &[Variable]) -> Result<Vec<u8>, String> {
    if let Some(v) = vars.iter().find(|v| v.data.len() != n) {
        return Err(format!(
            "{}: {} values for {n} points",
            v.name,
            v.data.len()
        ));
    }
    // Dimensions: point, then one string length per text variable.
    let mut dims: Vec<(String, usize)> = vec![("point".into(), n)];
    let mut var_dims: Vec<Vec<u32>> = Vec::new();
    for v in vars {
        match &v.data {
            Column::Text(t) => {
                var_dims.push(vec![0, dims.len() as u32]);
                dims.push((format!("{}_strlen", v.name), strlen(t)));
            }
            _ => var_dims.push(vec![0]),
        }
    }
    let vsize = |v: &Variable| -> usize {
        let raw = match &v.data {
            Column::Int(_) => 4 * n,
            Column::Double(_) => 8 * n,
            Column::Text(t) => strlen(t) * n,
        };
        raw.div_ceil(4) * 4
    };
    // The header, with placeholder offsets patched once its length is known.
    let mut h = Vec::new();
    h.extend_from_slice(b"CDF\x02");
    u32be(&mut h, 0); // numrecs: no record dimension
    u32be(&mut h, NC_DIMENSION);
    u32be(&mut h, dims.len() as u32);
    for (dn, len) in &dims {
        name(&mut h, dn);
        u32be(
            &mut h,
            u32::try_from(*len).map_err(|_| format!("dimension {dn} too long"))?,
        );
    }
    attrs(&mut h, globals);
    if vars.is_empty() {
        h.extend_from_slice(&[0; 8]);
    } else {
        u32be(&mut h, NC_VARIABLE);
        u32be(&mut h, vars.len() as u32);
    }
    let mut begin_at = Vec::new();
    for (v, d) in vars.iter().zip(&var_dims) {
        name(&mut h, &v.name);
        u32be(&mut h, d.len() as u32);
        for id in d {
            u32be(&mut h, *id);
        }
        let mut a = v.attrs.clone();
        if matches!(v.data, Column::Text(_)) {
            a.push(("_Encoding".into(), Attr::Text("utf-8".into())));
        }
        attrs(&mut h, &a);
        u32be(
            &mut h,
            match v.data {
                Column::Int(_) => NC_INT,
                Column::Double(_) => NC_DOUBLE,
                Column::Text(_) => NC_CHAR,
            },
        );
        // vsize is 32-bit; a variable over 4 GiB cannot be described (never for a table).
        u32be(
            &mut h,
            u32::try_from(vsize(v)).map_err(|_| format!("{}: too large", v.name))?,
        );
        begin_at.push(h.len());
        h.extend_from_slice(&[0; 8]);
    }
    let mut offset = h.len() as u64;
    for (k, v) in vars.iter().enumerate() {
        h[begin_at[k]..begin_at[k] + 8].copy_from_slice(&offset.to_be_bytes());
        offset += vsize(v) as u64;
    }
    for v in vars {
        match &v.data {
            Column::Int(x) => x.iter().for_each(|a| h.extend_from_slice(&a.to_be_bytes())),
            Column::Double(x) => x.iter().for_each(|a| h.extend_from_slice(&a.to_be_bytes())),
            Column::Text(t) => {
                let w = strlen(t);
                for s in t {
                    h.extend_from_slice(s.as_bytes());
                    h.extend(std::iter::repeat_n(0u8, w - s.len()));
                }
            }
        }
        pad4(&mut h);
    }
    Ok(h)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_bytes_of_a_small_file() {
        let vars = [
            Variable {
                name: "x".into(),
                attrs: vec![("units".into(), Attr::Text("Pa".into()))],
                data: Column::Double(vec![1.0, f64::NAN]),
            },
            Variable {
                name: "s".into(),
                attrs: vec![],
                data: Column::Text(vec!["ok".into(), "bad".into()]),
            },
        ];
        let b = write(2, &[("title".into(), Attr::Text("t".into()))], &vars).unwrap();
        assert_eq!(&b[..4], b"CDF\x02");
        assert_eq!(&b[4..8], &[0, 0, 0, 0]);
        assert_eq!(&b[8..16], &[0, 0, 0, 0x0A, 0, 0, 0, 2]);
        // dimension "point" = 2: name length 5, "point" padded to 8, length 2
        assert_eq!(&b[16..20], &[0, 0, 0, 5]);
        assert_eq!(&b[20..28], b"point\0\0\0");
        assert_eq!(&b[28..32], &[0, 0, 0, 2]);
        // The data: x (16 bytes) then s (2 x 3 chars, padded to 8), at the end.
        let tail = &b[b.len() - 24..];
        assert_eq!(&tail[..8], &1.0f64.to_be_bytes());
        assert!(f64::from_be_bytes(tail[8..16].try_into().unwrap()).is_nan());
        assert_eq!(&tail[16..], b"ok\0bad\0\0");
        assert!(write(3, &[], &vars).is_err());
    }
}

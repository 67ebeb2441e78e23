//! NumPy's `.npy` and `.npz` formats, parsed from bytes (the library reads no files: the front
//! end hands the bytes over, as it hands Matrix Market text to
//! [`super::config::parse_matrix_market`]).
//!
//! - `.npy` (NumPy's format versions 1.0, 2.0 and 3.0): the magic `\x93NUMPY`, the version, the
//!   header's length (2 bytes little-endian in 1.0, 4 in 2.0/3.0), a Python dict literal
//!   `{'descr': '<f8', 'fortran_order': False, 'shape': (n, n), }`, then the data. Read: real
//!   arrays of `f8`, `f4`, `i8`, `i4` (either byte order) in C or Fortran order, and 1-D arrays
//!   of unicode strings `U{k}` (UTF-32, the DOF table `np.array(["x0", "y0", …])`).
//! - `.npz` (`np.savez`, `np.savez_compressed`): a ZIP archive of `.npy` members named by the
//!   arrays' keywords. Read from its central directory (ZIP64 sizes and offsets included, as
//!   NumPy writes with `force_zip64`), members stored or deflated (method 0 or 8, inflated by
//!   `miniz_oxide`), each checked against its CRC-32.
//!
//! Why our own reader: the crates that read `.npz` (`npyz` with its `npz` feature,
//! `ndarray-npy`) bring the `zip` crate and its compression back ends into the library; the
//! subset NumPy writes is small, and `miniz_oxide` (pure Rust, already in the workspace's tree
//! through `png`) does the inflating. Errors are one line and say what is wrong and where.

/// An array read from a `.npy` file.
#[derive(Debug, Clone, PartialEq)]
pub enum NpyArray {
    /// A real array: its shape and its entries in row-major (C) order, as `f64`.
    Real {
        /// The shape.
        shape: Vec<usize>,
        /// The entries, row-major.
        data: Vec<f64>,
    },
    /// A 1-D array of strings (dtype `U{k}`).
    Strings(Vec<String>),
}

/// Largest number of entries accepted in one array (a `2000 × 2000` matrix, [`super::MAX_DOFS`]).
const MAX_ENTRIES: usize = super::MAX_DOFS * super::MAX_DOFS;

/// The value of `key` in NumPy's header dict literal (the text after `'key':` up to the next
/// top-level comma or the closing brace).
fn header_value<'a>(header: &'a str, key: &str) -> Result<&'a str, String> {
    let pat = format!("'{key}':");
    let start = header.find(&pat).ok_or_else(|| format!("header has no '{key}'"))? + pat.len();
    let rest = header[start..].trim_start();
    let end = if rest.starts_with('(') { rest.find(')').map(|i| i + 1) } else { rest.find([',', '}']) };
    Ok(rest[..end.ok_or_else(|| format!("header's '{key}' is not terminated"))?].trim())
}

/// Parse a `.npy` file's bytes (module docs).
pub fn parse_npy(bytes: &[u8]) -> Result<NpyArray, String> {
    if bytes.len() < 10 || &bytes[..6] != b"\x93NUMPY" {
        return Err("not a NumPy .npy array (no \\x93NUMPY magic)".into());
    }
    let (major, minor) = (bytes[6], bytes[7]);
    let (hlen, hstart): (usize, usize) = match major {
        1 => (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10),
        2 | 3 if bytes.len() >= 12 => (u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize, 12),
        _ => return Err(format!(".npy format version {major}.{minor} is not read (1.0, 2.0, 3.0)")),
    };
    let body = hstart.checked_add(hlen).filter(|e| *e <= bytes.len()).ok_or("the .npy header runs past the end of the file")?;
    let header = std::str::from_utf8(&bytes[hstart..body]).map_err(|_| "the .npy header is not text")?;
    let descr = header_value(header, "descr")?.trim_matches(|c| c == '\'' || c == '"');
    let fortran = match header_value(header, "fortran_order")? {
        "True" => true,
        "False" => false,
        o => return Err(format!("fortran_order is {o}, expected True or False")),
    };
    let shape_text = header_value(header, "shape")?;
    let shape: Vec<usize> = shape_text
        .trim_matches(|c| c == '(' || c == ')')
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse::<usize>().map_err(|_| format!("shape {shape_text}: \"{s}\" is not a whole number")))
        .collect::<Result<_, _>>()?;
    let count = shape
        .iter()
        .try_fold(1usize, |a, b| a.checked_mul(*b))
        .filter(|c| *c <= MAX_ENTRIES)
        .ok_or_else(|| format!("shape {shape_text}: more than {MAX_ENTRIES} entries"))?;
    let data = &bytes[body..];
    let (order, kind) = descr.split_at(1.min(descr.len()));
    let little = match order {
        "<" | "|" | "=" => true,
        ">" => false,
        _ => return Err(format!("dtype '{descr}' is not read (f8, f4, i8, i4, U)")),
    };
    if let Some(k) = kind.strip_prefix('U') {
        let k: usize = k.parse().map_err(|_| format!("dtype '{descr}' is not read"))?;
        if shape.len() != 1 {
            return Err(format!("a string array must be 1-D, has shape {shape_text}"));
        }
        let need = count.checked_mul(k).and_then(|c| c.checked_mul(4)).ok_or("string array too large")?;
        // more bytes than announced is refused as well: a header that understates the shape
        // would otherwise read a part of the array as the whole
        if data.len() != need {
            return Err(format!("{} bytes of data, the header announces {need}", data.len()));
        }
        let strings = (0..count)
            .map(|i| {
                (0..k)
                    .map(|c| {
                        let b = &data[4 * (i * k + c)..4 * (i * k + c) + 4];
                        let b = [b[0], b[1], b[2], b[3]];
                        if little {
                            u32::from_le_bytes(b)
                        } else {
                            u32::from_be_bytes(b)
                        }
                    })
                    .take_while(|u| *u != 0)
                    .map(|u| char::from_u32(u).ok_or_else(|| format!("string {i}: U+{u:X} is not a character")))
                    .collect::<Result<String, String>>()
            })
            .collect::<Result<_, _>>()?;
        return Ok(NpyArray::Strings(strings));
    }
    let size = match kind {
        "f8" | "i8" => 8,
        "f4" | "i4" => 4,
        _ => return Err(format!("dtype '{descr}' is not read (f8, f4, i8, i4, U)")),
    };
    // (a longer file was read up to the announced size and the rest ignored: a `(27, 27)`
    // header over a 28 × 28 array gave a matrix of the array's first 729 entries)
    if data.len() != count * size {
        return Err(format!("{} bytes of data, the header announces {}", data.len(), count * size));
    }
    let value = |i: usize| -> f64 {
        let b = &data[i * size..(i + 1) * size];
        let mut a8 = [0u8; 8];
        let mut a4 = [0u8; 4];
        if size == 8 {
            a8.copy_from_slice(b);
        } else {
            a4.copy_from_slice(b);
        }
        match (kind, little) {
            ("f8", true) => f64::from_le_bytes(a8),
            ("f8", false) => f64::from_be_bytes(a8),
            ("i8", true) => i64::from_le_bytes(a8) as f64,
            ("i8", false) => i64::from_be_bytes(a8) as f64,
            ("f4", true) => f32::from_le_bytes(a4) as f64,
            ("f4", false) => f32::from_be_bytes(a4) as f64,
            (_, true) => i32::from_le_bytes(a4) as f64,
            (_, false) => i32::from_be_bytes(a4) as f64,
        }
    };
    let mut out = vec![0.0; count];
    if fortran && shape.len() == 2 {
        let (r, c) = (shape[0], shape[1]);
        for j in 0..c {
            for i in 0..r {
                out[i * c + j] = value(j * r + i);
            }
        }
    } else if fortran && shape.len() > 2 {
        return Err(format!("a Fortran-ordered array of {} dimensions is not read", shape.len()));
    } else {
        for (i, o) in out.iter_mut().enumerate() {
            *o = value(i);
        }
    }
    Ok(NpyArray::Real { shape, data: out })
}

/// CRC-32 (IEEE 802.3, reflected, as ZIP uses).
fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in data {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
        }
    }
    !crc
}

fn u16_at(b: &[u8], i: usize) -> Result<u16, String> {
    b.get(i..i + 2).map(|s| u16::from_le_bytes([s[0], s[1]])).ok_or_else(|| "the .npz archive is cut short".to_string())
}

fn u32_at(b: &[u8], i: usize) -> Result<u32, String> {
    b.get(i..i + 4).map(|s| u32::from_le_bytes([s[0], s[1], s[2], s[3]])).ok_or_else(|| "the .npz archive is cut short".to_string())
}

fn u64_at(b: &[u8], i: usize) -> Result<u64, String> {
    b.get(i..i + 8).map(|s| u64::from_le_bytes([s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7]])).ok_or_else(|| "the .npz archive is cut short".to_string())
}

/// The members of a `.npz` archive: `(name without ".npy", the member's .npy bytes)`, in the
/// archive's order (module docs).
pub fn parse_npz(bytes: &[u8]) -> Result<Vec<(String, Vec<u8>)>, String> {
    if bytes.len() < 22 {
        return Err("not a NumPy .npz archive (shorter than a ZIP end record)".into());
    }
    // end of central directory: signature 0x06054b50, searched backwards over the comment
    let lo = bytes.len().saturating_sub(22 + 65_535);
    let eocd = (lo..=bytes.len().saturating_sub(22))
        .rev()
        .find(|&i| bytes[i..i + 4] == [0x50, 0x4b, 0x05, 0x06])
        .ok_or("not a NumPy .npz archive (no ZIP end of central directory)")?;
    // every offset read from the archive lies inside it, so that the offsets added to it below
    // cannot overflow (a ZIP64 record pointing at 2⁶⁴ − 1 panicked in a debug build)
    let inside = |o: u64, what: &str| -> Result<usize, String> {
        usize::try_from(o).ok().filter(|o| *o <= bytes.len()).ok_or_else(|| format!("the .npz archive's {what} lies past its end (damaged archive)"))
    };
    let mut entries = u16_at(bytes, eocd + 10)? as u64;
    let mut cd = u32_at(bytes, eocd + 16)? as u64;
    if (entries == 0xFFFF || cd == 0xFFFF_FFFF) && eocd >= 20 && u32_at(bytes, eocd - 20)? == 0x0706_4b50 {
        // ZIP64 end of central directory locator, then the record
        let rec = inside(u64_at(bytes, eocd - 12)?, "ZIP64 record")?;
        if u32_at(bytes, rec)? != 0x0606_4b50 {
            return Err("the .npz archive's ZIP64 record is damaged".into());
        }
        entries = u64_at(bytes, rec + 32)?;
        cd = u64_at(bytes, rec + 48)?;
    }
    let cd = inside(cd, "central directory")?;
    if entries > 1000 {
        return Err(format!("the .npz archive has {entries} members (at most 1000 read)"));
    }
    let mut out = vec![];
    let mut p = cd;
    for _ in 0..entries {
        if u32_at(bytes, p)? != 0x0201_4b50 {
            return Err("the .npz archive's central directory is damaged".into());
        }
        let method = u16_at(bytes, p + 10)?;
        let crc = u32_at(bytes, p + 16)?;
        let mut csize = u32_at(bytes, p + 20)? as u64;
        let mut usize_ = u32_at(bytes, p + 24)? as u64;
        let (nlen, xlen, clen) = (u16_at(bytes, p + 28)? as usize, u16_at(bytes, p + 30)? as usize, u16_at(bytes, p + 32)? as usize);
        let mut local = u32_at(bytes, p + 42)? as u64;
        let name = bytes.get(p + 46..p + 46 + nlen).ok_or("the .npz archive is cut short")?;
        let name = String::from_utf8_lossy(name).into_owned();
        // ZIP64 extra field (id 1): the 0xFFFFFFFF fields in order: size, compressed size, offset
        let mut x = p + 46 + nlen;
        let xend = x + xlen;
        while x + 4 <= xend {
            let (id, len) = (u16_at(bytes, x)?, u16_at(bytes, x + 2)? as usize);
            if id == 1 {
                let mut f = x + 4;
                for v in [&mut usize_, &mut csize, &mut local] {
                    if *v == 0xFFFF_FFFF && f + 8 <= x + 4 + len {
                        *v = u64_at(bytes, f)?;
                        f += 8;
                    }
                }
            }
            x += 4 + len;
        }
        p = xend + clen;
        let l = inside(local, &format!("member {name}'s local header"))?;
        if u32_at(bytes, l)? != 0x0403_4b50 {
            return Err(format!("{name}: the member's local header is damaged"));
        }
        let start = l + 30 + u16_at(bytes, l + 26)? as usize + u16_at(bytes, l + 28)? as usize;
        let raw = start
            .checked_add(csize as usize)
            .and_then(|e| bytes.get(start..e))
            .ok_or_else(|| format!("{name}: the member runs past the end of the archive"))?;
        let limit = (usize_ as usize).min(16 * MAX_ENTRIES + 4096);
        let data = match method {
            0 => raw.to_vec(),
            8 => miniz_oxide::inflate::decompress_to_vec_with_limit(raw, limit).map_err(|e| format!("{name}: cannot inflate ({:?})", e.status))?,
            m => return Err(format!("{name}: compression method {m} is not read (stored or deflated: np.savez, np.savez_compressed)")),
        };
        if data.len() as u64 != usize_ {
            return Err(format!("{name}: {} bytes, the archive announces {usize_}", data.len()));
        }
        if crc32(&data) != crc {
            return Err(format!("{name}: CRC-32 mismatch (damaged archive)"));
        }
        out.push((name.strip_suffix(".npy").unwrap_or(&name).to_string(), data));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc32_of_the_check_string() {
        // the standard check value of CRC-32/ISO-HDLC
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
    }

    #[test]
    fn npy_header_and_orders() {
        let mut b = b"\x93NUMPY\x01\x00".to_vec();
        let h = "{'descr': '<f8', 'fortran_order': True, 'shape': (2, 3), }";
        let mut h = h.to_string();
        while !(10 + h.len() + 1).is_multiple_of(64) {
            h.push(' ');
        }
        h.push('\n');
        b.extend_from_slice(&(h.len() as u16).to_le_bytes());
        b.extend_from_slice(h.as_bytes());
        // column-major 1..6: [[1, 3, 5], [2, 4, 6]]
        for v in 1..=6 {
            b.extend_from_slice(&(v as f64).to_le_bytes());
        }
        assert_eq!(parse_npy(&b).unwrap(), NpyArray::Real { shape: vec![2, 3], data: vec![1.0, 3.0, 5.0, 2.0, 4.0, 6.0] });
        let e = parse_npy(&b[..b.len() - 3]).unwrap_err();
        assert!(e.contains("bytes of data"), "{e}");
        assert!(parse_npy(b"hello world").unwrap_err().contains("magic"));
    }
}

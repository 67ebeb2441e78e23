//! `--parquet`: the rows of a CSV also as an Apache Parquet file (columnar, typed, read by
//! pandas, pyarrow, polars, DuckDB, Spark). One table of named columns: an optional first
//! `INT64` column (a sweep's `point`) and `DOUBLE`s, written in row groups of [`ROW_GROUP`] rows
//! as rows arrive, so memory stays bounded and an interrupted run keeps every full group plus
//! the last partial one (the footer is written by [`Table::finish`], also on interruption).
//! The rows go to a temporary file beside the final name ([`crate::outfile::TempName`]):
//! [`Table::finish`] writes the footer and renames it into place; a table dropped unfinished
//! (an error) removes it, so a footer-less file never appears under the final name.
//!
//! Built with the `parquet` crate (no Arrow, no compression codecs: the cheapest build that
//! writes standard files); the cargo feature `parquet` (on by default) can leave it out, and
//! `--parquet` then says how to get it.

use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};

/// Rows per row group: 64 Ki rows of ~15 doubles are ~8 MB buffered.
pub const ROW_GROUP: usize = 1 << 16;

/// A Parquet file being written row by row.
pub struct Table {
    path: PathBuf,
    /// The temporary file's name until [`Table::finish`] renames it.
    #[cfg(feature = "parquet")]
    temp: crate::outfile::TempName,
    #[cfg(feature = "parquet")]
    writer: parquet::file::writer::SerializedFileWriter<std::fs::File>,
    /// Whether column 0 is an integer column.
    #[cfg(feature = "parquet")]
    int_first: bool,
    /// Buffered rows, column by column.
    columns: Vec<Vec<f64>>,
}

impl Table {
    /// Create `path` with columns `names`, spelled as in the CSV (`drive.psi0[1]`; `int_first`:
    /// column 0 holds whole numbers, written as `INT64`).
    #[cfg(feature = "parquet")]
    pub fn create(path: &Path, names: &[String], int_first: bool) -> Result<Self> {
        use parquet::basic::{Repetition, Type as Physical};
        use parquet::schema::types::Type;
        use std::sync::Arc;
        let fields = names
            .iter()
            .enumerate()
            .map(|(i, n)| {
                let physical = if i == 0 && int_first { Physical::INT64 } else { Physical::DOUBLE };
                Type::primitive_type_builder(n, physical).with_repetition(Repetition::REQUIRED).build().map(Arc::new)
            })
            .collect::<parquet::errors::Result<Vec<_>>>()?;
        let schema = Arc::new(Type::group_type_builder("autobal").with_fields(fields).build()?);
        let props = parquet::file::properties::WriterProperties::builder().set_created_by(format!("autobal {}", env!("CARGO_PKG_VERSION"))).build();
        let (temp, file) = crate::outfile::TempName::create("--parquet", path)?;
        let writer = parquet::file::writer::SerializedFileWriter::new(file, schema, Arc::new(props))?;
        Ok(Table { path: path.to_path_buf(), temp, writer, int_first, columns: vec![vec![]; names.len()] })
    }

    /// Without the `parquet` feature: an error that says how to get it.
    #[cfg(not(feature = "parquet"))]
    pub fn create(path: &Path, _names: &[String], _int_first: bool) -> Result<Self> {
        bail!(
            "--parquet: this autobal was built without Parquet support (cargo feature `parquet`); {} not written. Rebuild with: cargo install --path crates/autobal-cli --features parquet",
            path.display()
        )
    }

    /// Append one row (one value per column).
    pub fn push(&mut self, row: &[f64]) -> Result<()> {
        if row.len() != self.columns.len() {
            bail!("{}: a row of {} values for {} columns", self.path.display(), row.len(), self.columns.len());
        }
        for (c, &v) in self.columns.iter_mut().zip(row) {
            c.push(v);
        }
        if self.columns[0].len() >= ROW_GROUP {
            self.flush()?;
        }
        Ok(())
    }

    /// Write the buffered rows as one row group.
    #[cfg(feature = "parquet")]
    fn flush(&mut self) -> Result<()> {
        use parquet::data_type::{DoubleType, Int64Type};
        if self.columns[0].is_empty() {
            return Ok(());
        }
        let mut group = self.writer.next_row_group()?;
        let mut i = 0;
        while let Some(mut col) = group.next_column()? {
            let values = std::mem::take(&mut self.columns[i]);
            if i == 0 && self.int_first {
                let ints: Vec<i64> = values.iter().map(|&v| v as i64).collect();
                col.typed::<Int64Type>().write_batch(&ints, None, None)?;
            } else {
                col.typed::<DoubleType>().write_batch(&values, None, None)?;
            }
            col.close()?;
            i += 1;
        }
        group.close()?;
        Ok(())
    }

    #[cfg(not(feature = "parquet"))]
    fn flush(&mut self) -> Result<()> {
        Ok(())
    }

    /// Write the last rows and the footer (without it the file cannot be read), and rename the
    /// file into place.
    pub fn finish(mut self) -> Result<PathBuf> {
        self.flush().with_context(|| format!("--parquet: cannot write {}", self.path.display()))?;
        #[cfg(feature = "parquet")]
        {
            self.writer.close().with_context(|| format!("--parquet: cannot write {}", self.path.display()))?;
            self.temp.rename()
        }
        #[cfg(not(feature = "parquet"))]
        Ok(self.path)
    }
}

#[cfg(all(test, feature = "parquet"))]
mod tests {
    use super::*;
    use parquet::file::reader::{FileReader, SerializedFileReader};
    use parquet::record::RowAccessor;

    #[test]
    fn rows_read_back_in_order_across_row_groups() {
        let dir = std::env::temp_dir().join(format!("autobal-parquet-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("t.parquet");
        let names: Vec<String> = ["point", "drive.psi0[1]", "peak"].iter().map(|s| s.to_string()).collect();
        let mut t = Table::create(&path, &names, true).unwrap();
        let n = ROW_GROUP + 7;
        for i in 0..n {
            t.push(&[i as f64, 0.1 * i as f64, f64::from_bits(0x3ff0_0000_0000_0001 + i as u64)]).unwrap();
        }
        assert!(t.push(&[1.0]).is_err());
        t.finish().unwrap();
        let r = SerializedFileReader::new(std::fs::File::open(&path).unwrap()).unwrap();
        let meta = r.metadata();
        assert_eq!(meta.num_row_groups(), 2);
        assert_eq!(meta.file_metadata().num_rows(), n as i64);
        let fields: Vec<String> = meta.file_metadata().schema_descr().columns().iter().map(|c| c.name().to_string()).collect();
        assert_eq!(fields, names);
        for (i, row) in r.get_row_iter(None).unwrap().enumerate() {
            let row = row.unwrap();
            assert_eq!(row.get_long(0).unwrap(), i as i64);
            assert_eq!(row.get_double(1).unwrap().to_bits(), (0.1 * i as f64).to_bits());
            assert_eq!(row.get_double(2).unwrap().to_bits(), 0x3ff0_0000_0000_0001 + i as u64);
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_table_dropped_unfinished_leaves_no_file() {
        // an error between create and finish: no footer-less file under any name
        let dir = std::env::temp_dir().join(format!("autobal-parquet-drop-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("t.parquet");
        let mut t = Table::create(&path, &["a".to_string()], false).unwrap();
        for i in 0..ROW_GROUP + 3 {
            t.push(&[i as f64]).unwrap();
        }
        drop(t);
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
        let t = Table::create(&path, &["a".to_string()], false).unwrap();
        assert!(!path.exists(), "the final name appears only when finished");
        t.finish().unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(&bytes[bytes.len() - 4..], b"PAR1");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

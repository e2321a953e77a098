//! Text documents: CSV with `#` header lines ([`Csv`]), aligned tables ([`reading`]) and the
//! numbers in their cells; a non-finite cell is refused with its place named.

use anyhow::Result;
use trirhythm_paper::table::Table;

/// The first non-finite cell of a table or CSV document, and how many there are.
#[derive(Default)]
struct NonFinite {
    first: Option<(String, usize, String, String)>,
    count: usize,
    /// Columns where ±∞ is a value (a limit: log p where p = 0, U_eff at A = 0).
    infinity_ok: Vec<String>,
}

impl NonFinite {
    /// Look at one row of cells (formatted by [`num`]).
    fn scan(&mut self, columns: &[String], row: usize, cells: &[String]) {
        for (i, c) in cells.iter().enumerate() {
            let ok = (c == "-inf" || c == "inf")
                && columns
                    .get(i)
                    .is_some_and(|name| self.infinity_ok.contains(name));
            if !ok && matches!(c.as_str(), "nan" | "inf" | "-inf" | "NaN") {
                self.count += 1;
                if self.first.is_none() {
                    let col = columns.get(i).cloned().unwrap_or_default();
                    let lead = format!(
                        "{} = {}",
                        columns.first().cloned().unwrap_or_default(),
                        cells.first().cloned().unwrap_or_default()
                    );
                    self.first = Some((col, row, lead, c.clone()));
                }
            }
        }
    }

    /// An error naming where, if any.
    fn check(&self) -> Result<()> {
        match &self.first {
            None => Ok(()),
            Some((col, row, lead, v)) => anyhow::bail!(
                "the computation produced a non-finite value: column {col} = {v} at row {row} \
                 ({lead}), {} such value(s) in all (overflow or an undefined quantity); nothing \
                 written",
                self.count
            ),
        }
    }
}

/// A CSV document: `#` comment lines, a header row, rows of numbers; the records written by
/// the `csv` crate ([`writer`]).
pub struct Csv {
    comments: String,
    records: csv::Writer<Vec<u8>>,
    columns: Vec<String>,
    rows: usize,
    nonfinite: NonFinite,
}

impl Csv {
    /// Start with comment lines (each prefixed by `# `) and the column names.
    pub fn new(comments: &[String], columns: &[&str]) -> Csv {
        let comments: String = comments
            .iter()
            .flat_map(|c| c.lines())
            .map(|l| format!("# {l}\n"))
            .collect();
        let mut records = writer();
        write(&mut records, columns.iter().copied());
        Csv {
            comments,
            records,
            columns: columns.iter().map(|c| c.to_string()).collect(),
            rows: 0,
            nonfinite: NonFinite::default(),
        }
    }

    /// Let `column` hold ±∞ where that is the value (a limit such as log 0): written as
    /// `inf`/`-inf`, not refused; NaN still is.
    pub fn allow_infinity(mut self, column: &str) -> Csv {
        self.nonfinite.infinity_ok.push(column.to_string());
        self
    }

    /// Append a row of cells (already formatted).
    pub fn row<I: IntoIterator<Item = String>>(&mut self, cells: I) {
        let cells: Vec<String> = cells.into_iter().collect();
        self.rows += 1;
        self.nonfinite.scan(&self.columns, self.rows, &cells);
        write(&mut self.records, cells.iter().map(String::as_str));
    }

    /// The document, or an error naming the first non-finite cell.
    pub fn finish(self) -> Result<String> {
        self.nonfinite.check()?;
        let bytes = self
            .records
            .into_inner()
            .map_err(|e| anyhow::anyhow!("writing CSV to memory: {}", e.error()))?;
        let records = String::from_utf8(bytes).expect("CSV of UTF-8 fields is UTF-8");
        Ok(self.comments + &records)
    }

    /// A library [`Table`] as a document: its notes as `#` lines, refused like any other.
    pub fn of(table: &Table) -> Result<String> {
        let columns: Vec<&str> = table.columns.iter().map(String::as_str).collect();
        let mut csv = Csv::new(&table.notes, &columns);
        for column in &table.infinite {
            csv = csv.allow_infinity(column);
        }
        for row in &table.rows {
            csv.row(row.iter().cloned());
        }
        csv.finish()
    }
}

/// A writer of CSV records into memory (RFC 4180, `\n` line ends): a field holding a comma, a
/// double quote, a line break or `#` (the files' comment character, which a reader skipping `#`
/// lines would take for a comment where it starts a row) is quoted, its quotes doubled (the
/// panel names of several figures hold commas). Rows are written as given, of any length.
fn writer() -> csv::Writer<Vec<u8>> {
    csv::WriterBuilder::new()
        .terminator(csv::Terminator::Any(b'\n'))
        .comment(Some(b'#'))
        .flexible(true)
        .from_writer(Vec::new())
}

/// Append one record to `w` (writing to memory cannot fail).
fn write<'a>(w: &mut csv::Writer<Vec<u8>>, fields: impl Iterator<Item = &'a str>) {
    w.write_record(fields)
        .expect("writing a CSV record to memory cannot fail");
}

/// Numbers for CSV cells (round-trip): the paper crate's.
pub use trirhythm_paper::notes::num;

/// An aligned text table, or an error naming its first non-finite cell (±∞ is allowed in the
/// columns named in `infinite`, where it is the value).
fn table(columns: &[&str], rows: &[Vec<String>], infinite: &[&str]) -> Result<String> {
    let mut nonfinite = NonFinite {
        infinity_ok: infinite.iter().map(|c| c.to_string()).collect(),
        ..Default::default()
    };
    let names: Vec<String> = columns.iter().map(|c| c.to_string()).collect();
    for (i, r) in rows.iter().enumerate() {
        nonfinite.scan(&names, i + 1, r);
    }
    nonfinite.check()?;
    let mut widths: Vec<usize> = columns.iter().map(|c| c.chars().count()).collect();
    for r in rows {
        for (i, cell) in r.iter().enumerate() {
            widths[i] = widths[i].max(cell.chars().count());
        }
    }
    let fmt_row = |cells: &mut dyn Iterator<Item = &str>| -> String {
        let cells: Vec<String> = cells
            .enumerate()
            .map(|(i, c)| format!("{c:>0$}", widths[i]))
            .collect();
        cells.join("  ") + "\n"
    };
    let mut out = fmt_row(&mut columns.iter().copied());
    for r in rows {
        out.push_str(&fmt_row(&mut r.iter().map(|s| s.as_str())));
    }
    Ok(out)
}

/// A library [`Table`] for reading: aligned, its notes as closing lines.
pub fn reading(t: &Table) -> Result<String> {
    let columns: Vec<&str> = t.columns.iter().map(String::as_str).collect();
    let infinite: Vec<&str> = t.infinite.iter().map(String::as_str).collect();
    let text = table(&columns, &t.rows, &infinite)?;
    Ok(text + &t.notes.iter().map(|n| format!("{n}\n")).collect::<String>())
}

#[cfg(test)]
mod tests {
    use super::{write, writer};

    /// One record as the documents write it.
    fn record<'a>(fields: impl Iterator<Item = &'a str>) -> String {
        let mut w = writer();
        write(&mut w, fields);
        String::from_utf8(w.into_inner().unwrap()).unwrap()
    }

    #[test]
    fn fields_with_commas_quotes_or_line_breaks_are_quoted() {
        assert_eq!(record(["1", "2.5", "-inf"].into_iter()), "1,2.5,-inf\n");
        assert_eq!(
            record(["(a) μ0 = 0.005, r = 0.99", "say \"hi\"", "x"].into_iter()),
            "\"(a) μ0 = 0.005, r = 0.99\",\"say \"\"hi\"\"\",x\n"
        );
        assert_eq!(record(["a\nb"].into_iter()), "\"a\nb\"\n");
        assert_eq!(record(["#1", "x#"].into_iter()), "\"#1\",\"x#\"\n");
    }
}

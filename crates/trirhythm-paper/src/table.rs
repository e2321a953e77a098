//! A figure's data as tables: the rows of numbers its CSV files hold, with their notes.
//!
//! A [`Table`] is a faithful view of a figure's data (no picture in it): the column names,
//! one row of cells per data point (numbers formatted by [`crate::notes::num`], round-trip
//! exact), the notes that go in the file's comment lines, and the columns where ±∞ is a value
//! (a limit such as log 0). [`crate::Figure::tables`] gives a figure's tables; the CLI writes
//! each as `figNN{suffix}.csv`, refusing NaN and ±∞ outside the columns that allow it.

/// One table of a figure's data.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// What follows `figNN` in the file name: `""` for the figure's main table, `"_pdf"`,
    /// `"_folds"`.
    pub suffix: &'static str,
    /// Notes: parameters, methods, verdicts (the file's comment lines).
    pub notes: Vec<String>,
    /// Column names.
    pub columns: Vec<String>,
    /// Rows of cells.
    pub rows: Vec<Vec<String>>,
    /// Columns where ±∞ is a value, not an overflow.
    pub infinite: Vec<String>,
}

impl Table {
    /// An empty main table with `notes` and `columns`.
    pub fn new(notes: &[String], columns: &[&str]) -> Table {
        Table {
            suffix: "",
            notes: notes.to_vec(),
            columns: columns.iter().map(|c| c.to_string()).collect(),
            rows: Vec::new(),
            infinite: Vec::new(),
        }
    }

    /// The same table under another file-name suffix.
    pub fn named(mut self, suffix: &'static str) -> Table {
        self.suffix = suffix;
        self
    }

    /// Let `column` hold ±∞ where that is the value (NaN still is not).
    pub fn allow_infinity(mut self, column: &str) -> Table {
        self.infinite.push(column.to_string());
        self
    }

    /// Append a row of cells (already formatted).
    pub fn row<I: IntoIterator<Item = String>>(&mut self, cells: I) {
        self.rows.push(cells.into_iter().collect());
    }
}

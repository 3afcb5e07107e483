//! A table as data: its columns are declared once (the CSV key, the Markdown heading, how a
//! row makes the cell, which Markdown table the column belongs to), and this one writer makes
//! the Markdown and the CSV from that declaration, so a CSV header cannot disagree with its
//! rows and a column cannot be in one file and forgotten in the other by accident.

/// One cell. Numbers carry the decimals Markdown shows; the CSV keeps full precision.
#[derive(Clone, Debug, PartialEq)]
pub enum Cell {
    /// No value: `-` in Markdown, an empty CSV field.
    Empty,
    /// A number with this many decimals in Markdown.
    Num(f64, usize),
    /// A number in scientific notation (3 decimals in Markdown).
    Sci(f64),
    /// A ratio: `1.23x` in Markdown.
    Times(f64),
    /// A fraction: `12.3%` in Markdown, the fraction in the CSV.
    Percent(f64),
    Int(i64),
    Text(String),
    /// `yes` / `no` in Markdown, `true` / `false` in the CSV.
    Flag(bool),
}

impl Cell {
    pub fn num(v: Option<f64>, decimals: usize) -> Self {
        v.map_or(Cell::Empty, |v| Cell::Num(v, decimals))
    }

    pub fn sci(v: Option<f64>) -> Self {
        v.map_or(Cell::Empty, Cell::Sci)
    }

    pub fn times(v: Option<f64>) -> Self {
        v.map_or(Cell::Empty, Cell::Times)
    }

    pub fn int(v: impl TryInto<i64>) -> Self {
        v.try_into().map_or(Cell::Empty, Cell::Int)
    }

    pub fn text(s: impl Into<String>) -> Self {
        Cell::Text(s.into())
    }

    pub fn markdown(&self) -> String {
        match self {
            Cell::Empty => "-".into(),
            Cell::Num(v, d) => format!("{v:.d$}"),
            Cell::Sci(v) => format!("{v:.3e}"),
            Cell::Times(v) => format!("{v:.2}x"),
            Cell::Percent(v) => format!("{:.1}%", 100.0 * v),
            Cell::Int(v) => v.to_string(),
            // A `|` would end the cell.
            Cell::Text(s) => s.replace('|', "/"),
            Cell::Flag(b) => if *b { "yes" } else { "no" }.into(),
        }
    }

    pub fn csv(&self) -> String {
        match self {
            Cell::Empty => String::new(),
            Cell::Num(v, _) | Cell::Times(v) | Cell::Percent(v) => format!("{v}"),
            Cell::Sci(v) => format!("{v:e}"),
            Cell::Int(v) => v.to_string(),
            Cell::Text(s) => csv_field(s),
            Cell::Flag(b) => b.to_string(),
        }
    }
}

/// A CSV field, quoted when it holds a comma, a quote or a line break.
pub fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// One column of a sheet of rows `R`.
pub struct Column<'a, R> {
    /// The CSV header; `None`: Markdown only.
    key: Option<String>,
    /// The Markdown heading; `None`: CSV only.
    heading: Option<String>,
    /// The Markdown table it is in; `None`: in every one (the columns that name the row).
    part: Option<&'static str>,
    cell: Box<dyn Fn(&R) -> Cell + 'a>,
}

impl<'a, R> Column<'a, R> {
    /// A column of both files.
    pub fn new(
        key: impl Into<String>,
        heading: impl Into<String>,
        cell: impl Fn(&R) -> Cell + 'a,
    ) -> Self {
        Self {
            key: Some(key.into()),
            heading: Some(heading.into()),
            part: None,
            cell: Box::new(cell),
        }
    }

    /// A CSV-only column (e.g. the scene's spec where Markdown shows its name).
    pub fn csv(key: impl Into<String>, cell: impl Fn(&R) -> Cell + 'a) -> Self {
        Self {
            key: Some(key.into()),
            heading: None,
            part: None,
            cell: Box::new(cell),
        }
    }

    /// A Markdown-only column (e.g. several CSV fields shown in one cell).
    pub fn md(heading: impl Into<String>, cell: impl Fn(&R) -> Cell + 'a) -> Self {
        Self {
            key: None,
            heading: Some(heading.into()),
            part: None,
            cell: Box::new(cell),
        }
    }

    /// Put the column in the Markdown table `part` (the CSV holds every part).
    pub fn part(mut self, part: &'static str) -> Self {
        self.part = Some(part);
        self
    }

    /// Leave the column out of the Markdown (keep it in the CSV).
    pub fn csv_only(mut self) -> Self {
        self.heading = None;
        self
    }
}

/// The columns of a table, in order.
pub struct Sheet<'a, R> {
    pub columns: Vec<Column<'a, R>>,
}

impl<'a, R> Sheet<'a, R> {
    pub fn new(columns: Vec<Column<'a, R>>) -> Self {
        Self { columns }
    }

    /// Add `columns` at the end.
    pub fn extend(&mut self, columns: impl IntoIterator<Item = Column<'a, R>>) {
        self.columns.extend(columns);
    }

    /// The header line and one line per row, every column with a key.
    pub fn csv(&self, rows: &[R]) -> String {
        let columns: Vec<&Column<R>> = self.columns.iter().filter(|c| c.key.is_some()).collect();
        let header: Vec<String> = columns
            .iter()
            .map(|c| csv_field(c.key.as_deref().unwrap_or_default()))
            .collect();
        let mut out = header.join(",") + "\n";
        for row in rows {
            let fields: Vec<String> = columns.iter().map(|c| (c.cell)(row).csv()).collect();
            out += &(fields.join(",") + "\n");
        }
        out
    }

    /// The Markdown table of every column with a heading (all parts).
    pub fn markdown(&self, rows: &[R]) -> String {
        self.markdown_of(rows, |_| true)
    }

    /// The Markdown table of `part`: the columns that name the row, then the part's.
    pub fn markdown_part(&self, rows: &[R], part: &str) -> String {
        self.markdown_of(rows, |p| p.is_none_or(|p| p == part))
    }

    fn markdown_of(&self, rows: &[R], keep: impl Fn(Option<&str>) -> bool) -> String {
        let columns: Vec<&Column<R>> = self
            .columns
            .iter()
            .filter(|c| c.heading.is_some() && keep(c.part))
            .collect();
        let mut md = String::from("|");
        for c in &columns {
            md += &format!(" {} |", c.heading.as_deref().unwrap_or_default());
        }
        md += "\n|";
        md += &"---|".repeat(columns.len());
        md += "\n";
        for row in rows {
            md += "|";
            for c in &columns {
                md += &format!(" {} |", (c.cell)(row).markdown());
            }
            md += "\n";
        }
        md
    }
}

/// `- note` lines under a `## Notes` heading.
pub fn notes_section<S: AsRef<str>>(notes: impl IntoIterator<Item = S>) -> String {
    let mut md = "## Notes\n\n".to_string();
    for n in notes {
        md += &format!("- {}\n", n.as_ref());
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Row {
        name: &'static str,
        ms: Option<f64>,
    }

    fn sheet<'a>() -> Sheet<'a, Row> {
        Sheet::new(vec![
            Column::new("name", "Name", |r: &Row| Cell::text(r.name)),
            Column::new("ms", "ms", |r: &Row| Cell::num(r.ms, 2)).part("timing"),
            Column::csv("ms_twice", |r: &Row| Cell::num(r.ms.map(|m| 2.0 * m), 2)).part("timing"),
            Column::md("fps", |r: &Row| Cell::num(r.ms.map(|m| 1000.0 / m), 0)).part("rates"),
        ])
    }

    fn rows() -> [Row; 2] {
        [
            Row {
                name: "a,b",
                ms: Some(1.23456),
            },
            Row {
                name: "c|d",
                ms: None,
            },
        ]
    }

    #[test]
    fn csv_has_one_field_per_key_in_every_row() {
        let csv = sheet().csv(&rows());
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(
            lines,
            ["name,ms,ms_twice", "\"a,b\",1.23456,2.46912", "c|d,,"]
        );
    }

    #[test]
    fn markdown_parts_keep_the_naming_columns() {
        let s = sheet();
        let md = s.markdown_part(&rows(), "timing");
        let lines: Vec<&str> = md.lines().collect();
        assert_eq!(
            lines,
            [
                "| Name | ms |",
                "|---|---|",
                "| a,b | 1.23 |",
                "| c/d | - |"
            ]
        );
        let all = s.markdown(&rows());
        assert!(all.starts_with("| Name | ms | fps |\n"), "{all}");
        assert!(all.contains("| a,b | 1.23 | 810 |"), "{all}");
    }

    #[test]
    fn cells_format_per_file() {
        assert_eq!(Cell::Times(1.5).markdown(), "1.50x");
        assert_eq!(Cell::Percent(0.125).markdown(), "12.5%");
        assert_eq!(Cell::Percent(0.125).csv(), "0.125");
        assert_eq!(Cell::Flag(true).markdown(), "yes");
        assert_eq!(Cell::Flag(false).csv(), "false");
        assert_eq!(Cell::Sci(2.5e-5).markdown(), "2.500e-5");
        assert_eq!(csv_field("say \"x\""), "\"say \"\"x\"\"\"");
    }
}

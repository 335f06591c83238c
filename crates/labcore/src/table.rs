//! Small live tables beside the canvas (an open list, a comparison of
//! planners), described as data like plots and drawn by the page.

/// One table: a caption, column headers and rows of already formatted cells.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    /// Stable key (DOM, tests).
    pub key: &'static str,
    pub caption: String,
    pub columns: Vec<String>,
    pub rows: Vec<Vec<String>>,
    /// A row to highlight (e.g. the node being expanded).
    pub highlight: Option<usize>,
}

impl Table {
    #[must_use]
    pub fn new(key: &'static str, caption: impl Into<String>, columns: &[&str]) -> Self {
        Self {
            key,
            caption: caption.into(),
            columns: columns.iter().map(|c| (*c).to_owned()).collect(),
            rows: Vec::new(),
            highlight: None,
        }
    }

    /// Appends a row; it is padded or cut to the number of columns.
    pub fn push_row(&mut self, mut cells: Vec<String>) {
        cells.resize(self.columns.len(), String::new());
        self.rows.push(cells);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_fit_the_columns() {
        let mut t = Table::new("open", "Open list", &["cell", "g", "h", "f"]);
        t.push_row(vec!["(1, 2)".into(), "1".into()]);
        t.push_row((0..6).map(|i| i.to_string()).collect());
        assert!(t.rows.iter().all(|r| r.len() == 4));
        assert_eq!(t.rows[0][3], "");
    }
}

//! `cargo xtask readme`: README's table of the experiments, written from the
//! registry (`labcore::catalogue::CATALOGUE`: number, id) and each content
//! file (`assets/<id>.json`: title, summary), between two markers. A test
//! fails when README's table is not what this would write, so adding an
//! experiment is its folder, its content file and its registry line, then
//! this command.

use crate::util::{self, step};
use labcore::catalogue::CATALOGUE;
use std::fs;

/// The line before the table.
pub const BEGIN: &str = "<!-- experiments: written by `cargo xtask readme` from the registry and assets/<id>.json; do not edit -->";
/// The line after it.
pub const END: &str = "<!-- experiments: end -->";

/// The table, one row per listed experiment in the lab's order: number, id,
/// title and summary from its content file.
pub fn experiments_table() -> Result<String, String> {
    let mut table =
        String::from("| # | id | experiment | what a student does |\n| --- | --- | --- | --- |\n");
    for planned in CATALOGUE.iter() {
        let entry = labcore::find(planned.id)
            .ok_or_else(|| format!("experiment {:?} is not in this build", planned.id))?;
        let content = entry
            .content()
            .map_err(|e| format!("assets/{}.json: {e}", planned.id))?;
        table.push_str(&format!(
            "| {} | `{}` | {} | {} |\n",
            planned.number,
            planned.id,
            cell(&content.title),
            cell(&content.summary)
        ));
    }
    Ok(table)
}

/// A text as one Markdown table cell.
fn cell(text: &str) -> String {
    text.replace('|', "\\|").replace('\n', " ")
}

/// `readme` with its table replaced by `table`; an error when the markers
/// are missing or out of order.
pub fn with_table(readme: &str, table: &str) -> Result<String, String> {
    let begin = readme
        .find(BEGIN)
        .ok_or_else(|| format!("README.md has no line {BEGIN}"))?;
    let after_begin = begin + BEGIN.len();
    let end = readme[after_begin..]
        .find(END)
        .map(|i| after_begin + i)
        .ok_or_else(|| format!("README.md has no line {END} after {BEGIN}"))?;
    Ok(format!(
        "{}\n\n{}\n{}",
        &readme[..after_begin],
        table,
        &readme[end..]
    ))
}

/// Rewrites README.md's table of the experiments.
pub fn readme() -> Result<(), String> {
    step("README.md: the table of the experiments");
    let path = util::root().join("README.md");
    let text =
        fs::read_to_string(&path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let updated = with_table(&text, &experiments_table()?)?;
    if updated == text {
        println!("README.md's table is up to date");
        return Ok(());
    }
    fs::write(&path, updated).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    println!(
        "README.md's table rewritten ({} experiments)",
        CATALOGUE.len()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn readme_table_of_the_experiments_is_what_cargo_xtask_readme_writes() {
        let text = fs::read_to_string(util::root().join("README.md")).unwrap();
        let expected = with_table(&text, &experiments_table().unwrap()).unwrap();
        assert!(
            text == expected,
            "README.md's table of the experiments is out of date: run `cargo xtask readme`"
        );
    }

    #[test]
    fn readme_table_has_a_row_per_listed_experiment_in_order() {
        let table = experiments_table().unwrap();
        let ids: Vec<&str> = table
            .lines()
            .skip(2)
            .map(|row| row.split('|').nth(2).unwrap().trim().trim_matches('`'))
            .collect();
        let listed: Vec<&str> = CATALOGUE.iter().map(|p| p.id).collect();
        assert_eq!(ids, listed);
    }

    #[test]
    fn a_readme_without_its_markers_is_an_error_not_a_rewrite() {
        assert!(with_table("# lab\n", "| t |\n").is_err());
        let swapped = format!("{END}\n{BEGIN}\n");
        assert!(with_table(&swapped, "| t |\n").is_err());
        let fine = format!("a\n{BEGIN}\nold\n{END}\nb\n");
        assert_eq!(
            with_table(&fine, "| new |\n").unwrap(),
            format!("a\n{BEGIN}\n\n| new |\n\n{END}\nb\n")
        );
    }

    #[test]
    fn a_pipe_in_a_title_or_summary_stays_inside_its_cell() {
        assert_eq!(cell("a | b\nc"), "a \\| b c");
    }
}

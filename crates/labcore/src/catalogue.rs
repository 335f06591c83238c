//! The lab's table of contents: every experiment in the lab's numbering,
//! grouped by topic, whether in this build or not.

pub use crate::experiments::{Group, Planned};

/// Every experiment of the lab, in its numbering: written from the one list
/// of experiments in `experiments/mod.rs`.
pub const CATALOGUE: [Planned; crate::experiments::LISTED] = crate::experiments::CATALOGUE;

/// The catalogue entry of an experiment id.
#[must_use]
pub fn planned(id: &str) -> Option<&'static Planned> {
    CATALOGUE.iter().find(|p| p.id == id)
}

/// The key of the wasm module that ships experiment `id` (`cargo xtask
/// dist` builds one module per key, holding only its experiments):
/// the one its line in `experiments/mod.rs` names, or its own id.
#[must_use]
pub fn wasm_module(id: &str) -> Option<&'static str> {
    crate::experiments::WASM_MODULES
        .iter()
        .find(|(of, _)| *of == id)
        .map(|(_, key)| *key)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_count_from_one_and_ids_are_unique() {
        for (i, p) in CATALOGUE.iter().enumerate() {
            assert_eq!(p.number as usize, i + 1);
            assert_eq!(CATALOGUE.iter().filter(|q| q.id == p.id).count(), 1);
        }
    }

    #[test]
    fn every_built_experiment_is_catalogued_with_its_content_number() {
        for entry in crate::registry() {
            let p = planned(entry.id).expect("catalogued");
            let content = entry.content().expect("content parses");
            assert_eq!(content.number, p.number, "{}", entry.id);
        }
    }
}

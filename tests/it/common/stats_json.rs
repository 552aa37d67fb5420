//! Reading a `--stats-json` file's stage rows, as the CLI writes them.

use std::path::Path;

/// One stage's row of a `--stats-json` file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StageRow {
    /// Whether the stage ran.
    pub ran: bool,
    /// Why it ran or was skipped.
    pub reason: String,
    /// The items it processed.
    pub items: u64,
    /// What an item is (`samples`, `photons`, …).
    pub unit: String,
    /// The rays it traced.
    pub rays: u64,
}

/// The row of stage `name` in the `--stats-json` file at `path` (panics when there is none).
pub fn stage_row(path: &Path, name: &str) -> StageRow {
    let json: serde_json::Value = serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
    let s = json["stages"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["stage"] == name)
        .unwrap_or_else(|| panic!("no stage {name} in {}", path.display()));
    StageRow {
        ran: s["ran"].as_bool().unwrap(),
        reason: s["reason"].as_str().unwrap().to_string(),
        items: s["items"].as_u64().unwrap(),
        unit: s["unit"].as_str().unwrap().to_string(),
        rays: s["rays"].as_u64().unwrap(),
    }
}

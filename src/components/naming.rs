//! Names and provenance: which scene element an entity came from.

use std::path::PathBuf;

/// The scene name of an element. Flattened instances carry their DAG path, e.g.
/// `world/table/leg_1`.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Name(pub String);

/// Where in the scene files an entity was declared, so that errors and statistics can point
/// at it (`file:line:column`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SourceLink {
    /// Scene or include file that declared the element.
    pub file: PathBuf,
    /// 1-based line.
    pub line: usize,
    /// 1-based column.
    pub column: usize,
}

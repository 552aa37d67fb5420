//! Scene loading: RON files → validated descriptions → an ECS world.
//!
//! STUB: replaced by the real loader (helper B). The API below is the contract.

use std::fmt;
use std::path::{Path, PathBuf};

use crate::settings::RenderSettings;

/// One problem found in a scene, located in a file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Diagnostic {
    /// File the problem is in.
    pub file: PathBuf,
    /// 1-based line.
    pub line: usize,
    /// 1-based column.
    pub column: usize,
    /// What is wrong and what was expected.
    pub message: String,
    /// A suggestion (`did you mean "chrome_red"?`).
    pub help: Option<String>,
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}:{}:{}: error: {}",
            self.file.display(),
            self.line,
            self.column,
            self.message
        )?;
        if let Some(help) = &self.help {
            write!(f, "\n  help: {help}")?;
        }
        Ok(())
    }
}

/// Every problem found in a scene, reported together.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SceneErrors(pub Vec<Diagnostic>);

impl fmt::Display for SceneErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, d) in self.0.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{d}")?;
        }
        Ok(())
    }
}

impl std::error::Error for SceneErrors {}

/// A loaded, validated scene.
pub struct LoadedScene {
    /// The world with every scene entity spawned.
    pub world: hecs::World,
    /// Settings from the scene's `options`.
    pub settings: RenderSettings,
    /// Non-fatal notes (e.g. degenerate triangles dropped).
    pub warnings: Vec<String>,
}

/// Loads and validates the scene at `path`.
pub fn load_scene(path: &Path) -> Result<LoadedScene, SceneErrors> {
    Err(SceneErrors(vec![Diagnostic {
        file: path.to_path_buf(),
        line: 1,
        column: 1,
        message: "scene loading is not implemented yet".into(),
        help: None,
    }]))
}

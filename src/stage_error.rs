//! How a stage can fail, as a typed enum with the one message a user reads.
//!
//! User errors that only show once stages run (overlapping bake UVs, a scatter over a surface
//! that turned out empty, a surface that cannot be diced) are not bugs: they carry the
//! scene position where one exists, or the element's name. [`StageError::Internal`] alone
//! means a broken invariant in stagelight itself. The CLI prints `Display` as it is and
//! takes the exit code from [`StageError::exit_code`].

use std::fmt;
use std::path::PathBuf;

use crate::scene::Diagnostic;

/// Errors a stage can end with.
#[derive(Debug)]
pub enum StageError {
    /// Problems in the scene found by a stage, each located in a scene file
    /// (`file:line:col: error: …` with a `help:` line).
    Scene(Vec<Diagnostic>),
    /// An object's geometry cannot be built (named object, no scene position known).
    Geometry {
        /// The object's name.
        object: String,
        /// What went wrong.
        message: String,
    },
    /// A bake request cannot be baked (named instance, no scene position known).
    Bake {
        /// The instance's name.
        instance: String,
        /// What went wrong.
        message: String,
    },
    /// Writing an output file failed.
    Write {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
    /// The user interrupted the run (SIGINT).
    Interrupted,
    /// A broken invariant: a bug in a run condition, the loader or a stage.
    Internal(String),
}

/// Exit status for scene and runtime errors.
pub const EXIT_ERROR: u8 = 1;
/// Exit status after an interruption (128 + SIGINT).
pub const EXIT_INTERRUPTED: u8 = 130;

impl StageError {
    /// The process exit status for this error: 130 when interrupted, 1 otherwise.
    pub fn exit_code(&self) -> u8 {
        match self {
            StageError::Interrupted => EXIT_INTERRUPTED,
            _ => EXIT_ERROR,
        }
    }
}

impl fmt::Display for StageError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StageError::Scene(diagnostics) => {
                for (i, d) in diagnostics.iter().enumerate() {
                    if i > 0 {
                        writeln!(f)?;
                    }
                    write!(f, "{d}")?;
                }
                Ok(())
            }
            StageError::Geometry { object, message } => {
                write!(f, "error: object \"{object}\": {message}")
            }
            StageError::Bake { instance, message } => {
                write!(
                    f,
                    "error: bake request on instance \"{instance}\": {message}"
                )
            }
            StageError::Write { path, message } => {
                write!(f, "error: cannot write {}: {message}", path.display())
            }
            StageError::Interrupted => write!(f, "interrupted; no output written"),
            StageError::Internal(message) => {
                write!(f, "error: internal error (a bug in stagelight): {message}")
            }
        }
    }
}

impl std::error::Error for StageError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_variant_prints_one_message_with_its_exit_code() {
        let located = StageError::Scene(vec![Diagnostic {
            file: "scene.ron".into(),
            line: 3,
            column: 7,
            message: "bake request on instance \"a\": its UVs overlap".into(),
            help: Some("set `uvs: Unwrap`".into()),
        }]);
        assert_eq!(
            located.to_string(),
            "scene.ron:3:7: error: bake request on instance \"a\": its UVs overlap\n  help: set `uvs: Unwrap`"
        );
        let geometry = StageError::Geometry {
            object: "ball".into(),
            message: "radius is 0".into(),
        };
        assert_eq!(geometry.to_string(), "error: object \"ball\": radius is 0");
        let write = StageError::Write {
            path: "out/a.png".into(),
            message: "is a directory".into(),
        };
        assert_eq!(
            write.to_string(),
            "error: cannot write out/a.png: is a directory"
        );
        assert_eq!(
            StageError::Internal("no render camera".into()).to_string(),
            "error: internal error (a bug in stagelight): no render camera"
        );
        assert_eq!(StageError::Interrupted.exit_code(), 130);
        for e in [located, geometry, write] {
            assert_eq!(e.exit_code(), 1);
        }
    }
}

//! The syntax a scene file is written in, so that a help text shows what to write in that
//! file: `output "contour" "ps" "lines.ps"` for a mental ray scene, `(file: "lines.svg")`
//! for RON. Each reader's [`super::import::Format`] names its syntax; the loader keeps it
//! with every file it reads (`SourceFile::syntax`).

/// The syntax of one scene file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Syntax {
    /// stagelight's own RON description (and a file whose format is not known).
    #[default]
    Ron,
    /// RenderMan RIB.
    Rib,
    /// mental ray `.mi`.
    Mi,
    /// glTF 2.0 (`.gltf`, `.glb`).
    Gltf,
}

impl Syntax {
    /// The help text for this syntax: `mi` for a mental ray file, `ron` for the others (RIB
    /// and glTF have no statement for the options and outputs these helps name; RON is
    /// what `stagelight convert` turns them into).
    pub fn help(self, ron: &str, mi: &str) -> String {
        match self {
            Self::Mi => mi.to_string(),
            Self::Ron | Self::Rib | Self::Gltf => ron.to_string(),
        }
    }
}

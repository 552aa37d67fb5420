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
    /// what `stagelight convert` turns them into). Where a RIB or glTF scene can meet the
    /// help, [`Self::help_each`] says what to do in those.
    pub fn help(self, ron: &str, mi: &str) -> String {
        match self {
            Self::Mi => mi.to_string(),
            Self::Ron | Self::Rib | Self::Gltf => ron.to_string(),
        }
    }

    /// The help text for this syntax, one written for each.
    pub fn help_each(self, helps: Helps<'_>) -> String {
        match self {
            Self::Ron => helps.ron,
            Self::Mi => helps.mi,
            Self::Rib => helps.rib,
            Self::Gltf => helps.gltf,
        }
        .to_string()
    }

    /// A value's name as this syntax writes it, for a message about it: `mi` for a mental
    /// ray file (its statement word or shader parameter), `rib` for RIB (its request or
    /// parameter), `ron` (RON's field) for RON and glTF, whose values the messages name by
    /// their RON fields.
    pub fn named<'a>(self, ron: &'a str, mi: &'a str, rib: &'a str) -> &'a str {
        match self {
            Self::Mi => mi,
            Self::Rib => rib,
            Self::Ron | Self::Gltf => ron,
        }
    }

    /// The format's name as messages write it: `RIB`, `glTF`, `.mi`, `RON`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Ron => "RON",
            Self::Rib => "RIB",
            Self::Mi => ".mi",
            Self::Gltf => "glTF",
        }
    }
}

/// One help text per syntax, for [`Syntax::help_each`].
#[derive(Debug, Clone, Copy)]
pub struct Helps<'a> {
    /// For a RON scene.
    pub ron: &'a str,
    /// For a mental ray `.mi` scene.
    pub mi: &'a str,
    /// For a RIB scene.
    pub rib: &'a str,
    /// For a glTF scene.
    pub gltf: &'a str,
}

/// The command that writes the scene at `scene` as RON beside it (`stagelight convert
/// scene.rib -o scene.ron`), for helps that need what only RON can say.
pub fn convert_command(scene: &std::path::Path) -> String {
    let ron = scene.with_extension("ron");
    format!(
        "stagelight convert {} -o {}",
        scene.display(),
        ron.display()
    )
}

//! `stagelight convert`: any description a reader produced, written back as RON that the
//! RON reader loads into the same description (so it renders the same bytes).

use crate::scene::desc::SceneDesc;

/// The description as RON text: struct names, one value per line, `Some` implicit.
pub fn to_ron(desc: &SceneDesc) -> Result<String, ron::Error> {
    let config = ron::ser::PrettyConfig::new()
        .struct_names(true)
        .extensions(ron::extensions::Extensions::IMPLICIT_SOME);
    let mut text = ron::ser::to_string_pretty(desc, config)?;
    text.push('\n');
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::import::rib::read_rib;

    #[test]
    fn ron_round_trips_a_rib_scene() {
        let rib =
            "Format 32 24 1\nDisplay \"a.png\" \"file\" \"rgba\"\nTranslate 0 0 5\nWorldBegin\n\
                   LightSource \"spotlight\" 1 \"coneangle\" 0.4\nSurface \"plastic\" \"Ks\" 0.25\n\
                   Opacity [0.5 0.5 0.5]\nSphere 1 -0.5 1 300\nWorldEnd\n";
        let scene = read_rib(std::path::Path::new("a.rib"), rib.as_bytes()).unwrap();
        let text = to_ron(&scene.desc).unwrap();
        let back: SceneDesc = ron::Options::default()
            .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
            .from_str(&text)
            .unwrap_or_else(|e| panic!("{e}\n{text}"));
        assert_eq!(format!("{back:?}"), format!("{:?}", scene.desc));
        assert!(
            text.starts_with("#![enable(implicit_some)]\nScene("),
            "{text}"
        );
    }
}

//! `render --camera NAME`: moves the [`RenderCamera`] mark of a loaded scene to another of
//! its cameras (a RON scene's `cameras` entries, a glTF file's perspective cameras), so the
//! run renders that camera's view, resolution and outputs.

use std::path::Path;

use hecs::{Entity, World};

use crate::components::{Camera, Name, RenderCamera};
use crate::scene::syntax::{convert_command, Helps, Syntax};

/// The names of the scene's cameras, in entity order.
pub fn camera_names(world: &World) -> Vec<String> {
    let mut cameras: Vec<(Entity, String)> = world
        .query::<(Entity, &Name, &Camera)>()
        .iter()
        .map(|(e, n, _)| (e, n.0.clone()))
        .collect();
    cameras.sort_by_key(|(e, _)| e.to_bits());
    cameras.into_iter().map(|(_, n)| n).collect()
}

/// How the scene file `scene`, written in `syntax`, chooses its render camera, as a help
/// for `render --camera NAME` where only the scene's own render camera can be rendered (a
/// farm part, whose merge renders that camera): RON's `render: (camera: …)`, the camera
/// instance of a `.mi` `render` statement; a RIB file declares one camera, and a glTF file
/// renders its first, so those leave out `--camera` or move to RON.
pub fn render_camera_help(syntax: Syntax, scene: &Path, name: &str) -> String {
    let ron = format!("set `render: (camera: \"{name}\")` in the scene instead");
    syntax.help_each(Helps {
        ron: &ron,
        mi: &format!(
            "name that camera instance in the scene's `render` statement instead (`render \"…\" \"{name}\" \"…\"`)"
        ),
        rib: "a RIB file declares one camera (the transformation current at `WorldBegin`, named \"camera\"): leave out --camera",
        gltf: &format!(
            "a glTF file renders the first camera of its nodes: write the scene as RON (`{}`) and set `render: (camera: \"{name}\")` there",
            convert_command(scene)
        ),
    })
}

/// Makes the camera named `name` the render camera. An unknown name is an error message
/// (`error: --camera "x": …` with a help line listing the scene's cameras); nothing changes.
pub fn use_camera(world: &mut World, name: &str) -> Result<(), String> {
    let found = world
        .query::<(Entity, &Name, &Camera)>()
        .iter()
        .find(|(_, n, _)| n.0 == name)
        .map(|(e, ..)| e);
    let Some(camera) = found else {
        let names = camera_names(world);
        let help = if names.is_empty() {
            "the scene has no cameras".to_string()
        } else {
            let quoted: Vec<String> = names.iter().map(|n| format!("\"{n}\"")).collect();
            format!("the scene's cameras: {}", quoted.join(", "))
        };
        return Err(format!(
            "error: --camera \"{name}\": the scene has no camera of that name\n  help: {help}"
        ));
    };
    let marked: Vec<Entity> = world
        .query::<(Entity, &RenderCamera)>()
        .iter()
        .map(|(e, _)| e)
        .collect();
    for e in marked {
        // The entity was just queried, so removing its mark cannot fail.
        let _ = world.remove_one::<RenderCamera>(e);
    }
    // As above: the camera entity exists.
    let _ = world.insert_one(camera, RenderCamera);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::load_scene_str;

    const TWO_CAMERAS: &str = r#"Scene(
    cameras: [
        (name: "front", fov_y: 40.0, resolution: (8, 8),
         placement: LookAt(eye: (0, 0, 5), target: (0, 0, 0), up: (0, 1, 0)), outputs: []),
        (name: "side", fov_y: 40.0, resolution: (6, 4),
         placement: LookAt(eye: (5, 0, 0), target: (0, 0, 0), up: (0, 1, 0)), outputs: []),
    ],
    objects: [(name: "tri", mesh: Inline(vertices: [(0, 0, 0), (1, 0, 0), (0, 1, 0)], polygons: [[0, 1, 2]]))],
    instances: [(name: "tri_1", of: "tri")],
    groups: [(name: "world", members: ["tri_1"])],
    render: (root: "world", camera: "front"),
)"#;

    fn render_camera(world: &World) -> (String, u32) {
        let mut q = world.query::<(&Name, &Camera, &RenderCamera)>();
        let marked: Vec<(String, u32)> = q.iter().map(|(n, c, _)| (n.0.clone(), c.width)).collect();
        assert_eq!(marked.len(), 1);
        marked.into_iter().next().unwrap()
    }

    #[test]
    fn a_named_camera_becomes_the_render_camera() {
        let mut scene = load_scene_str(TWO_CAMERAS, std::path::Path::new("two.ron")).unwrap();
        assert_eq!(render_camera(&scene.world), ("front".to_string(), 8));
        use_camera(&mut scene.world, "side").unwrap();
        assert_eq!(render_camera(&scene.world), ("side".to_string(), 6));
    }

    #[test]
    fn an_unknown_name_lists_the_cameras() {
        let mut scene = load_scene_str(TWO_CAMERAS, std::path::Path::new("two.ron")).unwrap();
        assert_eq!(
            use_camera(&mut scene.world, "top").unwrap_err(),
            "error: --camera \"top\": the scene has no camera of that name\n  help: the scene's cameras: \"front\", \"side\""
        );
        assert_eq!(render_camera(&scene.world), ("front".to_string(), 8));
    }
}

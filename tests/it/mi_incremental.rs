//! mental ray's `incremental`: `incremental camera|light|material|shader|object|instance|…
//! "name" …` redefines an element defined earlier, replacing it; `incremental` of a name
//! never defined is a located error with a did-you-mean, and a redefinition without
//! `incremental` stays "defined twice".

use std::path::Path;

use stagelight::scene::desc::ShaderDesc;
use stagelight::scene::import::mi::{read_mi, MiScene};

/// A small scene (the camera 8 × 6, a grey material); `extra` goes before the instances.
fn scene(extra: &str) -> String {
    format!(
        "options \"opt\"
object space
end options
camera \"cam\"
resolution 8 6
focal 1
aperture 1
end camera
light \"lamp\" \"mib_light_point\" (\"color\" 1 1 1) origin 0 0 0 end light
material \"mtl\" \"mib_illum_lambert\" (\"diffuse\" 0.8 0.8 0.8, \"lights\" [\"lamp_inst\"]) end material
object \"quad\" group
1 1 -1  1 -1 -1  -1 -1 -1  -1 1 -1
v 0 v 1 v 2 v 3
p \"mtl\" 0 3 2 1
end group end object
{extra}
instance \"cam_inst\" \"cam\" end instance
instance \"lamp_inst\" \"lamp\" end instance
instance \"quad_inst\" \"quad\" end instance
instgroup \"root\" \"cam_inst\" \"lamp_inst\" \"quad_inst\" end instgroup
render \"root\" \"cam_inst\" \"opt\"
"
    )
}

fn read(text: &str) -> Result<MiScene, String> {
    read_mi(Path::new("x.mi"), text.as_bytes()).map_err(|problems| {
        problems
            .iter()
            .map(|p| p.to_string())
            .collect::<Vec<_>>()
            .join("\n")
    })
}

#[test]
fn incremental_replaces_the_earlier_definition() {
    let text = scene(
        "incremental camera \"cam\"
resolution 4 3
focal 1
aperture 1
end camera
incremental material \"mtl\" \"mib_illum_lambert\" (\"diffuse\" 0.2 0.4 0.6, \"lights\" [\"lamp_inst\"]) end material",
    );
    let read = read(&text).unwrap();
    assert_eq!(read.desc.cameras.len(), 1);
    assert_eq!(read.desc.cameras[0].resolution, (4, 3));
    assert_eq!(read.desc.materials.len(), 1);
    match &read.desc.materials[0].shader {
        ShaderDesc::Local { color, .. } => assert_eq!(*color, (0.2, 0.4, 0.6)),
        other => panic!("{other:?}"),
    }
}

#[test]
fn incremental_of_an_undefined_name_is_a_located_error() {
    let text = scene("incremental camera \"cma\"\nresolution 4 3\nend camera");
    assert_eq!(
        read(&text).err().unwrap(),
        "x.mi:16:20: error: incremental \"cma\": no element \"cma\" is defined before\n  help: did you mean \"cam\"?"
    );
    let text = scene("incremental render \"cam\"");
    assert_eq!(
        read(&text).err().unwrap(),
        "x.mi:16:13: error: expected a definition after incremental, found \"render\""
    );
}

#[test]
fn a_redefinition_without_incremental_is_defined_twice() {
    let text = scene("camera \"cam\"\nresolution 4 3\nend camera");
    assert_eq!(
        read(&text).err().unwrap(),
        "x.mi:16:8: error: \"cam\" is defined twice\n  help: the first is at x.mi:4:8"
    );
}

//! mental ray's `incremental`: `incremental camera|light|material|shader|object|instance|…
//! "name" …` changes an element defined earlier, starting from its earlier values: what the
//! block states overrides, what it leaves out keeps its value (for each kind, a block that
//! changes one value and the others kept); `incremental` of a name never defined is a
//! located error with a did-you-mean, and a redefinition without `incremental` stays
//! "defined twice".

use std::path::Path;

use stagelight::scene::desc::{SceneDesc, ShaderDesc};
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
fn incremental_values_written_again_override_the_earlier_ones() {
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

/// A scene with a value other than the default for each statement the tests change or
/// keep; `changes` goes after the instances.
fn rich(changes: &str) -> String {
    format!(
        "options \"opt\"
object space
samples 0 2
trace depth 3 3 6
end options
camera \"cam\"
resolution 8 6
focal 2
aperture 1
output \"rgba\" \"png\" \"a.png\"
end camera
light \"lamp\" \"mib_light_point\" (\"color\" 1 1 1, \"atten\" on, \"start\" 1, \"stop\" 5) origin 1 2 3 end light
shader \"sh\" \"mib_illum_lambert\" (\"diffuse\" 0.8 0.8 0.8, \"ambience\" 1 1 1, \"ambient\" 0.1 0.2 0.3, \"lights\" [\"lamp_inst\"])
material \"mtl\" \"mib_illum_lambert\" (\"diffuse\" 0.8 0.8 0.8, \"ambience\" 1 1 1, \"ambient\" 0.1 0.2 0.3, \"lights\" [\"lamp_inst\"]) end material
material \"other\" \"mib_illum_lambert\" (\"diffuse\" 0.5 0.5 0.5) end material
object \"quad\" shadow off group
1 1 -1  1 -1 -1  -1 -1 -1  -1 1 -1
v 0 v 1 v 2 v 3
p \"mtl\" 0 3 2 1
end group end object
instance \"cam_inst\" \"cam\" end instance
instance \"lamp_inst\" \"lamp\" end instance
instance \"quad_inst\" \"quad\" transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 -5 1 material \"mtl\" end instance
{changes}
instgroup \"root\" \"cam_inst\" \"lamp_inst\" \"quad_inst\" end instgroup
render \"root\" \"cam_inst\" \"opt\"
"
    )
}

/// The description of `rich(changes)`.
fn desc(changes: &str) -> SceneDesc {
    read(&rich(changes)).unwrap().desc
}

fn material<'a>(d: &'a SceneDesc, name: &str) -> &'a stagelight::scene::desc::MaterialDesc {
    d.materials.iter().find(|m| m.name == name).unwrap()
}

/// The diffuse colour and the ambient term of a `mib_illum_lambert` material.
fn lambert(d: &SceneDesc, name: &str) -> ((f64, f64, f64), (f64, f64, f64)) {
    match &material(d, name).shader {
        ShaderDesc::Local { color, ambient, .. } => (*color, *ambient),
        other => panic!("{other:?}"),
    }
}

fn debug<T: std::fmt::Debug + ?Sized>(v: &T) -> String {
    format!("{v:?}")
}

#[test]
fn incremental_options_keep_the_statements_not_repeated() {
    let base = desc("");
    let d = desc("incremental options \"opt\"\ntrace depth 1 1 2\nend options");
    let (o, b) = (d.options.unwrap(), base.options.unwrap());
    assert_eq!(
        (o.reflection_depth, o.refraction_depth, o.max_depth),
        (1, 1, 3)
    );
    // `samples 0 2` (adaptive 1…16) and `object space` (the quad placed at z −5) kept.
    assert_eq!(debug(&o.samples), debug(&b.samples));
    assert!(debug(&o.samples).contains("Adaptive"), "{:?}", o.samples);
    assert_eq!(debug(&d.instances), debug(&base.instances));
}

#[test]
fn incremental_camera_keeps_focal_aperture_and_outputs() {
    let d = desc("incremental camera \"cam\"\nresolution 4 3\nend camera");
    let cam = &d.cameras[0];
    assert_eq!(cam.resolution, (4, 3));
    // focal 2, aperture 1 kept: fov = 2·atan(aperture / (2·focal·aspect)).
    let fov = 2.0 * (1.0f64 / (2.0 * 2.0 * (4.0 / 3.0))).atan().to_degrees();
    assert!((cam.fov_y - fov).abs() < 1e-9, "{} vs {fov}", cam.fov_y);
    assert_eq!(cam.outputs.len(), 1);
    assert_eq!(cam.outputs[0].file, "a.png");
    // Outputs are one list: an incremental block that states one replaces them.
    let d = desc("incremental camera \"cam\"\noutput \"rgb\" \"png\" \"b.png\"\nend camera");
    let files: Vec<_> = d.cameras[0]
        .outputs
        .iter()
        .map(|o| o.file.as_str())
        .collect();
    assert_eq!(files, ["b.png"]);
    assert_eq!(d.cameras[0].resolution, (8, 6));
}

#[test]
fn incremental_light_keeps_unstated_parameters_and_statements() {
    let base = desc("");
    let d = desc("incremental light \"lamp\" \"mib_light_point\" (\"color\" 0.5 0.25 1) end light");
    let (l, b) = (&d.lights[0], &base.lights[0]);
    assert_eq!(l.color, (0.5, 0.25, 1.0));
    // `atten on, start 1, stop 5` and `origin 1 2 3` kept.
    assert_eq!(l.attenuation, Some((1.0, 5.0)));
    assert_eq!(debug(&l.kind), debug(&b.kind));
    assert!(debug(&l.kind).contains("(1.0, 2.0, 3.0)"), "{:?}", l.kind);
    // The shader may be left out: a statement alone changes its value.
    let d = desc("incremental light \"lamp\"\norigin 4 5 6\nend light");
    assert_eq!(d.lights[0].color, b.color);
    assert_eq!(d.lights[0].attenuation, Some((1.0, 5.0)));
    assert!(debug(&d.lights[0].kind).contains("(4.0, 5.0, 6.0)"));
}

#[test]
fn incremental_material_keeps_unstated_parameters() {
    let d = desc(
        "incremental material \"mtl\" \"mib_illum_lambert\" (\"diffuse\" 0.2 0.4 0.6) end material",
    );
    assert_eq!(lambert(&d, "mtl"), ((0.2, 0.4, 0.6), (0.1, 0.2, 0.3)));
    assert_eq!(
        material(&d, "mtl").lights,
        Some(vec!["lamp_inst".to_string()])
    );
}

#[test]
fn incremental_shader_keeps_unstated_parameters() {
    let d = desc(
        "incremental shader \"sh\" \"mib_illum_lambert\" (\"diffuse\" 0.2 0.4 0.6)
material \"from_sh\" = \"sh\" end material",
    );
    assert_eq!(lambert(&d, "from_sh"), ((0.2, 0.4, 0.6), (0.1, 0.2, 0.3)));
    assert_eq!(
        material(&d, "from_sh").lights,
        Some(vec!["lamp_inst".to_string()])
    );
    // Another shader type replaces the call whole.
    let d = desc(
        "incremental shader \"sh\" \"mib_illum_phong\" (\"diffuse\" 0.2 0.4 0.6)
material \"from_sh\" = \"sh\" end material",
    );
    assert_eq!(lambert(&d, "from_sh").1, (0.0, 0.0, 0.0));
}

#[test]
fn incremental_instance_keeps_its_transform() {
    let base = desc("");
    let d = desc("incremental instance \"quad_inst\" material \"other\" end instance");
    let find = |d: &SceneDesc| {
        d.instances
            .iter()
            .find(|i| i.name == "quad_inst")
            .cloned()
            .unwrap()
    };
    let (i, b) = (find(&d), find(&base));
    assert_eq!(i.material.as_deref(), Some("other"));
    assert_eq!(i.of, "quad");
    assert!(!b.transform.is_empty());
    assert_eq!(debug(&i.transform), debug(&b.transform));
}

#[test]
fn incremental_object_keeps_its_geometry_or_replaces_it_whole() {
    let base = desc("");
    let d = desc("incremental object \"quad\" visible off end object");
    let (o, b) = (&d.objects[0], &base.objects[0]);
    assert_eq!(o.visible, Some(false));
    assert_eq!(o.shadow, Some(false));
    assert_eq!(debug(&o.mesh), debug(&b.mesh));
    // A group replaces the geometry whole; the flags are kept.
    let d = desc(
        "incremental object \"quad\" group
0 0 -1  1 0 -1  0 1 -1
v 0 v 1 v 2
p \"mtl\" 0 1 2
end group end object",
    );
    assert_eq!(d.objects[0].shadow, Some(false));
    assert_ne!(debug(&d.objects[0].mesh), debug(&b.mesh));
}

/// What loading `files` (the first the scene) from a scratch folder says, the folder's
/// path left out.
fn load(name: &str, files: &[(&str, &str)]) -> String {
    let dir = crate::common::scratch_root().join(format!(
        "stagelight_mi_incremental_{name}_{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    for (file, text) in files {
        std::fs::write(dir.join(file), text).unwrap();
    }
    let got = match stagelight::scene::load_scene(&dir.join(files[0].0)) {
        Ok(_) => "ok".to_string(),
        Err(e) => e.to_string(),
    };
    got.replace(&format!("{}/", dir.display()), "")
        .trim_end()
        .to_string()
}

#[test]
fn values_of_an_incremental_block_are_located_in_it() {
    let text = rich("incremental camera \"cam\"\nresolution 0 3\nend camera");
    assert_eq!(
        load("own", &[("x.mi", &text)]),
        "x.mi:25:12: error: resolution width must be at least 1, found 0\n  help: the image is width × height pixels, each at least 1: `resolution 640 480`"
    );
}

#[test]
fn kept_values_stay_located_where_they_were_written() {
    // The earlier `resolution 0 6` is kept by a block that changes the focal length: the
    // error points at it, also when the change is in another file.
    let bad = rich("incremental camera \"cam\"\nfocal 3\nend camera")
        .replace("resolution 8 6", "resolution 0 6");
    assert_eq!(
        load("kept", &[("x.mi", &bad)]),
        "x.mi:7:12: error: resolution width must be at least 1, found 0\n  help: the image is width × height pixels, each at least 1: `resolution 640 480`"
    );
    let main = rich("$include \"change.mi\"").replace("resolution 8 6", "resolution 0 6");
    assert_eq!(
        load(
            "kept_included",
            &[
                ("x.mi", &main),
                (
                    "change.mi",
                    "incremental camera \"cam\"\nfocal 3\nend camera\n"
                )
            ]
        ),
        "x.mi:7:12: error: resolution width must be at least 1, found 0\n  help: the image is width × height pixels, each at least 1: `resolution 640 480`"
    );
}

#[test]
fn the_earlier_blocks_warnings_are_not_repeated() {
    let text = rich("incremental camera \"cam\"\nresolution 4 3\nend camera")
        .replace("aperture 1\n", "aperture 1\nclip 0.1 100\n");
    let warnings: Vec<String> = read(&text)
        .unwrap()
        .warnings
        .iter()
        .map(|w| w.to_string())
        .collect();
    assert_eq!(
        warnings,
        ["x.mi:10:1: warning: camera \"clip\" is read but not mapped"]
    );
}

//! RIB structure end to end: later frames, retained objects (`ObjectBegin`/`ObjectInstance`),
//! motion blocks, the light list as an attribute, the standard requests that are read and
//! ignored, and the warnings that say what value was used instead.

use std::path::Path;

use stagelight::components::{Camera, RenderCamera};
use stagelight::scene::desc::TransformDesc;
use stagelight::scene::import::rib::{read_rib, RibScene};

use crate::common::read_rib_text;
use stagelight::scene::load_scene_str;

/// The scene read from `text` as `t.rib` (a panic shows the reader's errors).
fn read(text: &str) -> RibScene {
    read_rib_text(text)
}

fn warnings(text: &str) -> Vec<String> {
    read(text)
        .warnings
        .iter()
        .map(ToString::to_string)
        .collect()
}

/// The beauty image of a RIB scene (its own resolution, 2 samples per pixel) and its width.
fn render(text: &str) -> (usize, Vec<glam::Vec3>) {
    let mut scene =
        load_scene_str(text, Path::new("t.rib")).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let mut width = 0;
    for (camera, _) in scene.world.query_mut::<(&Camera, &RenderCamera)>() {
        width = camera.width as usize;
    }
    let mut settings = scene.settings.clone();
    settings.spp = 2;
    let frame = crate::common::render(&mut scene.world, settings);
    (width, frame.outputs.image.expect("an image").beauty)
}

const HEAD: &str =
    "Format 32 16 1\nProjection \"perspective\" \"fov\" [40]\nTranslate 0 0 8\nWorldBegin\n";

#[test]
fn only_the_first_frame_is_read_and_later_frames_are_one_warning() {
    let text = "Format 64 48 1\nFrameBegin 1\nWorldBegin\nTranslate 0 0 3\nSphere 1 -1 1 360\n\
                WorldEnd\nFrameEnd\nFrameBegin 2\nWorldBegin\nTranslate 0 0 3\n\
                Sphere 0.5 -1 1 360\nWorldEnd\nFrameEnd\nFrameBegin 3\nFrameEnd\n";
    let s = read(text);
    assert_eq!(s.desc.objects.len(), 1);
    assert!(format!("{:?}", s.desc.objects[0].mesh).contains("radius: 1.0"));
    let w: Vec<String> = s.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(
        w,
        ["t.rib:8:1: warning: ignored this frame and every later one: only the first frame is rendered"]
    );
}

#[test]
fn an_object_is_drawn_only_where_it_is_instanced_with_the_attributes_there() {
    let define =
        "LightSource \"ambientlight\" 1\nObjectBegin \"ball\"\nSphere 1 -1 1 360\nObjectEnd\n";
    // A definition alone draws nothing.
    let alone = read(&format!("{HEAD}{define}WorldEnd\n"));
    assert!(alone.desc.objects.is_empty() && alone.desc.instances.is_empty());
    let place = |x: f64, c: &str| {
        format!("AttributeBegin\nTranslate {x} 0 0\nColor [{c}]\nSurface \"constant\"\nObjectInstance \"ball\"\nAttributeEnd\n")
    };
    let text = format!(
        "{HEAD}{define}{}{}WorldEnd\n",
        place(-1.5, "1 0 0"),
        place(1.5, "0 1 0")
    );
    let s = read(&text);
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    // One mesh, placed twice; the second instance's attributes make another material.
    assert_eq!(s.desc.objects.len(), 1);
    assert_eq!(s.desc.instances.len(), 2);
    assert_eq!(s.desc.instances[0].material, None);
    assert_eq!(s.desc.instances[1].material.as_deref(), Some("constant_2"));
    let (w, image) = render(&text);
    let at = |x: usize| image[8 * w + x];
    assert!(at(12).x > 0.9 && at(12).y < 0.1, "left: {}", at(12));
    assert!(at(20).y > 0.9 && at(20).x < 0.1, "right: {}", at(20));
    assert_eq!(at(16), glam::Vec3::ZERO, "nothing in between");
}

#[test]
fn attributes_inside_an_object_definition_are_warnings() {
    let w = warnings(&format!(
        "{HEAD}ObjectBegin 1\nColor [1 0 0]\nSphere 1 -1 1 360\nObjectEnd\nObjectInstance 1\nWorldEnd\n"
    ));
    assert_eq!(
        w,
        ["t.rib:6:1: warning: ignored \"Color\" inside ObjectBegin 1: an object takes its attributes where it is instanced"]
    );
}

#[test]
fn a_motion_block_uses_its_first_sample() {
    let s = read(
        "WorldBegin\nTranslate 0 0 5\nMotionBegin [0 1]\nTranslate 0 0 0\nTranslate 3 0 0\n\
         MotionEnd\nSphere 1 -1 1 360\nMotionBegin [0 1]\nScale 1 1 1\nScale 2 2 2\nMotionEnd\n\
         WorldEnd\n",
    );
    let [TransformDesc::Matrix(m)] = &s.desc.instances[0].transform[..] else {
        panic!("{:?}", s.desc.instances[0].transform)
    };
    assert_eq!((m[0][3], m[1][3], m[2][3]), (0.0, 0.0, -5.0));
    let w: Vec<String> = s.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(
        w,
        ["t.rib:3:1: warning: motion blur is not rendered: each motion block uses its first time sample"]
    );
}

#[test]
fn a_light_declared_in_an_attribute_block_is_off_after_it() {
    let text = format!(
        "{HEAD}Surface \"matte\"\nAttributeBegin\n\
         LightSource \"pointlight\" 1 \"from\" [0 0 -8] \"intensity\" [64]\n\
         Translate -1.5 0 0\nSphere 1 -1 1 360\nAttributeEnd\n\
         Translate 1.5 0 0\nSphere 1 -1 1 360\nWorldEnd\n"
    );
    let s = read(&text);
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    assert_eq!(s.desc.materials[0].lights, None);
    assert_eq!(s.desc.materials[1].lights, Some(Vec::new()));
    let (w, image) = render(&text);
    assert!(image[8 * w + 12].x > 0.05, "lit: {}", image[8 * w + 12]);
    assert_eq!(image[8 * w + 20], glam::Vec3::ZERO, "the light is off");
    // Illuminate switches it back on after the block.
    let again = text.replace("Translate 1.5 0 0\n", "Illuminate 1 1\nTranslate 1.5 0 0\n");
    let s = read(&again);
    assert!(s.desc.materials.iter().all(|m| m.lights.is_none()));
}

#[test]
fn standard_requests_we_do_not_map_are_located_warnings() {
    let w = warnings(
        "ArchiveRecord \"comment\" \"hello\"\nDisplay \"x.png\" \"file\" \"rgb\" \"quantize\" [0 0 0 0]\n\
         ErrorHandler \"print\"\nFormat 64 48 0\nPixelSamples 0 0\nWorldBegin\n\
         TextureCoordinates 0 0 1 0 0 1 1 1\nSolidBegin \"union\"\nSphere 1 -1 1 360\nSolidEnd\n\
         Shader \"a\" \"b\"\nResource \"r\" \"texture\"\nCamera \"c\"\nScopedCoordinateSystem \"s\"\n\
         ArchiveRecord \"structure\" \"Frames 1\"\nWorldEnd\n",
    );
    assert_eq!(
        w,
        [
            "t.rib:2:30: warning: ignored parameter \"quantize\" of Display",
            "t.rib:3:1: warning: ignored request \"ErrorHandler\"",
            "t.rib:4:14: warning: pixel aspect ratio 0 is not positive: using 1 (square pixels, the display's default)",
            "t.rib:5:14: warning: PixelSamples 0 is below 1, taken as 1: rendering 1 × 1 samples per pixel",
            "t.rib:7:1: warning: ignored request \"TextureCoordinates\"",
            "t.rib:8:1: warning: ignored request \"SolidBegin\": solids are not combined: the primitives inside are rendered as surfaces",
            "t.rib:10:1: warning: ignored request \"SolidEnd\"",
            "t.rib:11:1: warning: ignored request \"Shader\"",
            "t.rib:12:1: warning: ignored request \"Resource\"",
            "t.rib:13:1: warning: ignored request \"Camera\"",
            "t.rib:14:1: warning: ignored request \"ScopedCoordinateSystem\"",
        ]
    );
    let Err(e) = read_rib(
        Path::new("t.rib"),
        b"ArchiveRecrod \"comment\" \"x\"\nWorldBegin\nWorldEnd\n",
    ) else {
        panic!("an unknown request is an error")
    };
    assert_eq!(
        e.iter().map(ToString::to_string).collect::<Vec<_>>(),
        ["t.rib:1:1: error: unknown request \"ArchiveRecrod\"\n  help: did you mean \"ArchiveRecord\"?"]
    );
}

#[test]
fn display_mode_a_writes_the_alpha_as_a_grey_png() {
    let dir = crate::common::cli::scratch_dir("rib-display-a");
    std::fs::write(
        dir.join("a.rib"),
        "Display \"a.png\" \"file\" \"a\"\nFormat 16 16 1\nPixelSamples 1 1\n\
         PixelFilter \"box\" 1 1\nWorldBegin\nTranslate 0 0 3\nSphere 1 -1 1 360\nWorldEnd\n",
    )
    .unwrap();
    let o = crate::common::cli::run_in(&dir, &["render", "a.rib"]);
    assert!(o.status.success(), "{}", crate::common::cli::stderr_of(&o));
    let png =
        stagelight::image_io::png_codec::decode_png(&std::fs::read(dir.join("a.png")).unwrap())
            .unwrap();
    assert_eq!((png.width, png.height, png.channels), (16, 16, 1));
    let stagelight::image_io::png_codec::Samples::Eight(grey) = png.samples else {
        panic!("8-bit")
    };
    assert_eq!(
        (grey[8 * 16 + 8], grey[0]),
        (255, 0),
        "covered centre, empty corner"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn illuminate_takes_an_area_light_handle() {
    let area = "AttributeBegin\nAreaLightSource \"arealight\" 3 \"intensity\" [2]\n\
                Translate 0 0 1\nDisk 0 0.3 360\n";
    // Switched on: accepted without a word (an emitting surface lights every primitive).
    let on = format!("{HEAD}{area}Illuminate 3 1\nAttributeEnd\nIlluminate 3 1\nWorldEnd\n");
    let s = read(&on);
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    assert!(s.desc.materials.iter().all(|m| m.lights.is_none()));
    // Switched off inside the block: `AttributeEnd` switches it on again, so the sphere
    // after it is lit, without a word (RISpec: the light list is an attribute).
    let emission_of_disk = |s: &RibScene| {
        let name = s.desc.objects[0].material.clone().expect("a material");
        let m = s.desc.materials.iter().find(|m| m.name == name).unwrap();
        m.emission
    };
    let restored =
        format!("{HEAD}{area}Illuminate 3 0\nAttributeEnd\nSphere 1 -1 1 360\nWorldEnd\n");
    let s = read(&restored);
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    assert_eq!(emission_of_disk(&s), (2.0, 2.0, 2.0));
    // Off for every primitive but its own disk: switched off for the whole scene, the
    // disk emits nothing.
    let dark = format!("{HEAD}{area}AttributeEnd\nIlluminate 3 0\nSphere 1 -1 1 360\nWorldEnd\n");
    let s = read(&dark);
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    assert_eq!(emission_of_disk(&s), (0.0, 0.0, 0.0));
    // Off for some primitives only: it stays on, with a located warning naming both counts.
    let some = format!(
        "{HEAD}{area}AttributeEnd\nSphere 1 -1 1 360\nIlluminate 3 0\nSphere 1 -1 1 360\n\
         Sphere 2 -2 2 360\nWorldEnd\n"
    );
    assert_eq!(
        warnings(&some),
        [
            "t.rib:11:14: warning: Illuminate cannot switch off area light 3 for the 2 \
             primitives declared while it is off: it lights 1 other primitive, and an area \
             light's surfaces light every primitive or none\n  help: it stays on for every \
             primitive; it is switched off when every primitive but its own surfaces is \
             declared while it is off"
        ]
    );
    assert_eq!(emission_of_disk(&read(&some)), (2.0, 2.0, 2.0));
    // A LightSource taking the handle over is switched as one.
    let over = format!(
        "{HEAD}{area}AttributeEnd\nLightSource \"pointlight\" 3\nIlluminate 3 0\n\
         Sphere 1 -1 1 360\nWorldEnd\n"
    );
    let s = read(&over);
    assert!(s
        .desc
        .materials
        .iter()
        .any(|m| m.lights == Some(Vec::new())));
    // An unknown handle is still an error.
    let Err(unknown) = read_rib(
        Path::new("t.rib"),
        format!("{HEAD}Illuminate 4 0\nWorldEnd\n").as_bytes(),
    ) else {
        panic!("refused");
    };
    assert_eq!(
        unknown.iter().map(ToString::to_string).collect::<Vec<_>>(),
        ["t.rib:5:12: error: unknown light handle 4"]
    );
}

//! Farm parts merge exactly: for every example scene (at a reduced resolution), rendering it
//! as N parts (N = 1, 2, 3, 7; tiles and samples splits) and merging the part files gives
//! the single render's frame buffers bit for bit, and the same camera-space passes.

use std::path::Path;

use crate::common::example_scenes;
use stagelight::camera_space::CameraSpace;
use stagelight::components::{Camera, Pass, RenderCamera};
use stagelight::exr_output::encode_exr;
use stagelight::farm::merge::{merge, LoadedPart};
use stagelight::farm::part_file::{decode, encode};
use stagelight::farm::{part_file, Part, PartRun, Split};
use stagelight::frame::Frame;
use stagelight::framebuffer::FrameBuffers;
use stagelight::scene::load_scene;

/// Renders `path` shrunk to at most 20 pixels across with at most 2 samples (adaptive
/// sampling capped at 8) and at most 20,000 photons per map (every part traces the whole
/// maps: they are what most of a part's time went to), as `part` when given. Returns the buffers (with exact sums for a
/// part), the effective settings' frame and the camera space the EXR writer derives from.
fn render(path: &Path, part: Option<Part>) -> (FrameBuffers, Frame, CameraSpace) {
    let mut scene = load_scene(path).unwrap_or_else(|e| panic!("{}:\n{e}", path.display()));
    for (camera, _) in scene.world.query_mut::<(&mut Camera, &RenderCamera)>() {
        let scale = (20.0 / camera.width.max(camera.height) as f32).min(1.0);
        camera.width = ((camera.width as f32 * scale).round() as u32).max(1);
        camera.height = ((camera.height as f32 * scale).round() as u32).max(1);
    }
    let mut settings = scene.settings.clone();
    settings.spp = settings.spp.min(2);
    if let Some(a) = &mut settings.adaptive {
        a.max = a.max.min(8);
        a.min = a.min.min(a.max);
    }
    let photons = &mut settings.photons;
    for map in [&mut photons.caustics, &mut photons.global_illumination]
        .into_iter()
        .flatten()
    {
        map.photons = map.photons.min(20_000);
    }
    let mut frame = Frame::new(settings);
    frame.inputs.part = part.map(|part| PartRun {
        part,
        scene: path.display().to_string(),
        scene_hash: 1,
    });
    let stages: Vec<_> = stagelight::systems::STAGES
        .iter()
        .copied()
        .filter(|s| s.name != "write_output")
        .collect();
    stagelight::schedule::run_stages(&stages, &mut scene.world, &mut frame)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    // A part past the last tile (N = 7 of a 20-pixel-wide image) shades nothing: its part
    // file holds the empty buffers `write_output` writes for it.
    let fb = (frame.outputs.image.take())
        .or_else(|| stagelight::systems::shade::idle_part_image(&scene.world, &frame))
        .expect("an image");
    let camera = CameraSpace::of_render_camera(&scene.world, frame.inputs.settings.disabled)
        .expect("a render camera");
    (fb, frame, camera)
}

/// Part `part` of `path`, through its part file as `stagelight merge` reads it.
fn part_of(path: &Path, part: Part) -> LoadedPart {
    let (fb, frame, _) = render(path, Some(part));
    let run = frame.inputs.part.as_ref().unwrap();
    let file = part_file(run, &frame.inputs.settings, &fb).expect("a part keeps its sums");
    let bytes = encode(&file).unwrap();
    LoadedPart {
        path: format!("part_{}.exr", part.index).into(),
        file: decode(&bytes).unwrap(),
    }
}

/// Every pass (the camera-space passes of `camera` in a second file: they share channel
/// names with `Depth` and `Normal`), as bytes, and the per-pixel sample counts.
fn bits(fb: &FrameBuffers, camera: &CameraSpace) -> (Vec<u8>, Vec<u8>, Vec<u32>) {
    let all = [
        Pass::Beauty,
        Pass::Depth,
        Pass::Normal,
        Pass::ObjectId,
        Pass::MaterialId,
    ];
    (
        encode_exr(fb, camera, &all).unwrap(),
        encode_exr(fb, camera, &Pass::CAMERA_SPACE).unwrap(),
        fb.samples.clone(),
    )
}

#[test]
fn every_example_scene_merges_bit_identically_for_any_part_count_and_split() {
    for path in example_scenes() {
        let (single, frame, camera) = render(&path, None);
        let adaptive = frame.inputs.settings.adaptive.is_some();
        let expected = bits(&single, &camera);
        for split in [Split::Tiles, Split::Samples] {
            if split == Split::Samples && adaptive {
                continue;
            }
            for count in [1, 2, 3, 7] {
                let parts: Vec<LoadedPart> = (1..=count)
                    .map(|index| {
                        part_of(
                            &path,
                            Part {
                                index,
                                count,
                                split,
                            },
                        )
                    })
                    .collect();
                let merged = merge(&parts).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                assert!(
                    bits(&merged, &camera) == expected,
                    "{}: {count} parts, {split} split differ from the single render",
                    path.display()
                );
            }
        }
    }
}

#[test]
fn a_part_alone_does_not_merge_and_names_the_missing_ones() {
    let path = example_scenes()
        .into_iter()
        .find(|p| p.ends_with("cornell_box.ron"))
        .unwrap();
    let part = |index| {
        part_of(
            &path,
            Part {
                index,
                count: 3,
                split: Split::Tiles,
            },
        )
    };
    let e = merge(&[part(2)]).err().unwrap();
    assert_eq!(
        e,
        "missing parts 1/3, 3/3\n  help: re-run `stagelight render --part K/3` for K = 1, 3 (or resubmit array indices 1,3)"
    );
    let e = merge(&[part(1), part(2), part(2), part(3)]).err().unwrap();
    assert_eq!(
        e,
        "part 2/3 is given twice: part_2.exr and part_2.exr\n  help: pass each part file once"
    );
}

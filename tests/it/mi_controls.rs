//! Issue 13: the `.mi` scene controls that map onto engine options — the photon statements
//! of `options` (`caustic`, `globillum`, `finalgather`) become the photon maps, so the seed's
//! caustics scene traces photons; malformed statements give exact located messages.

use std::path::{Path, PathBuf};

use stagelight::components::LightPhotons;
use stagelight::scene::desc::{
    FaceDesc, PhotonDepthDesc, PhotonFilterDesc, PhotonMapDesc, PhotonMapFileDesc,
};
use stagelight::scene::import::mi::read_mi;
use stagelight::scene::load_scene;

fn dir(sub: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(sub)
}

fn fixture_text(options: &str) -> String {
    std::fs::read_to_string(dir("tests/fixtures/mi_controls/caustic_filter.mi"))
        .unwrap()
        .replace("caustic on\ncaustic filter tent\n", options)
}

#[test]
fn the_seed_caustic_options_map_onto_the_caustic_map() {
    let path = dir("assets/seeds/mi/caustics.mi");
    let read = read_mi(&path, &std::fs::read(&path).unwrap()).unwrap();
    let options = read.desc.options.expect("options");
    // caustic on / accuracy 700 .05 / filter cone 1.1.
    let want = PhotonMapDesc {
        gather: 700,
        radius: 0.05,
        filter: PhotonFilterDesc::Cone { k: 1.1 },
        ..PhotonMapDesc::default()
    };
    assert_eq!(options.caustics, Some(want));
    assert_eq!(options.global_illumination, None);
    // photonmap file "mrphotonmap.cpm".
    assert_eq!(
        options.photon_map,
        Some(PhotonMapFileDesc {
            file: "mrphotonmap.cpm".into(),
            rebuild: false
        })
    );
    // photon trace depth 4 4: four reflections, four refractions, eight in all.
    let depth = PhotonDepthDesc {
        reflection: Some(4),
        refraction: Some(4),
        sum: Some(8),
    };
    assert_eq!(options.photon_depth, Some(depth));
    let warned: Vec<String> = read
        .warnings
        .iter()
        .map(|w| w.problem.message.clone())
        .collect();
    assert!(
        !warned.iter().any(|w| w.contains("\"caustic\"")
            || w.contains("photonmap")
            || w.contains("\"photon\"")),
        "{warned:?}"
    );
}

#[test]
fn photon_trace_depth_defaults_its_refraction_and_sum_as_mental_ray() {
    for (statement, want) in [
        ("photon trace depth 2\n", (2, 2, 4)),
        ("photon trace depth 3 1\n", (3, 1, 4)),
        ("photon trace depth 3 1 2\n", (3, 1, 2)),
    ] {
        let text = fixture_text(statement);
        let read = read_mi(Path::new("depth.mi"), text.as_bytes()).unwrap();
        assert!(read.warnings.is_empty(), "{:?}", read.warnings);
        let depth = read.desc.options.unwrap().photon_depth.unwrap();
        assert_eq!(
            (depth.reflection, depth.refraction, depth.sum),
            (Some(want.0), Some(want.1), Some(want.2)),
            "{statement}"
        );
    }
}

#[test]
fn globillum_and_finalgather_map_onto_the_global_map() {
    let text = fixture_text(
        "globillum accuracy 64 0.5\nglobillum on\nfinalgather on\nfinalgather accuracy 32\n\
         caustic accuracy 20\nphotonmap rebuild on\nphotonmap file \"gi.pmap\"\n",
    );
    let read = read_mi(Path::new("gi.mi"), text.as_bytes()).unwrap();
    let options = read.desc.options.unwrap();
    let want = PhotonMapDesc {
        gather: 64,
        radius: 0.5,
        final_gather: 32,
        ..PhotonMapDesc::default()
    };
    assert_eq!(options.global_illumination, Some(want));
    assert_eq!(
        options.caustics, None,
        "accuracy alone does not turn a map on"
    );
    assert_eq!(
        options.photon_map,
        Some(PhotonMapFileDesc {
            file: "gi.pmap".into(),
            rebuild: true
        })
    );
    assert!(read.warnings.is_empty(), "{:?}", read.warnings);
    // Turned off again by a later statement; final gathering without the map warns.
    let text = fixture_text("globillum on\nglobillum off\nfinalgather on\n");
    let read = read_mi(Path::new("gi.mi"), text.as_bytes()).unwrap();
    assert_eq!(read.desc.options.unwrap().global_illumination, None);
    let warned: Vec<String> = read.warnings.iter().map(|w| w.to_string()).collect();
    assert_eq!(
        warned,
        [
            "gi.mi:5:1: warning: final gathering uses the global-illumination photon map here; \
          add \"globillum on\" to gather"
        ]
    );
}

#[test]
fn the_seed_caustics_scene_traces_caustic_photons() {
    let mut scene = load_scene(&dir("assets/seeds/mi/caustics.mi")).unwrap();
    for photons in scene.world.query_mut::<&mut LightPhotons>() {
        photons.caustic_photons = photons.caustic_photons.map(|n| n.min(3000));
    }
    assert!(scene.settings.photons.caustics.is_some());
    let mut settings = scene.settings.clone();
    // Keep the maps in memory (the seed names a photon map file).
    settings.photon_map = None;
    let frame = crate::common::through_photons(&mut scene.world, settings);
    let maps = frame.outputs.photons.expect("trace_photons ran");
    let stored = maps.caustics.map_or(0, |m| m.map.len());
    assert!(stored > 100, "{stored} caustic photons stored");
}

const MALFORMED: &[(&str, &str)] = &[
    (
        "caustic_accuracy",
        "tests/fixtures/mi_controls/caustic_accuracy.mi:4:18: error: caustic accuracy must be at least 2 photons per estimate, found 1",
    ),
    (
        "caustic_filter",
        "tests/fixtures/mi_controls/caustic_filter.mi:4:16: error: expected box, cone or gauss after caustic filter, found \"tent\"",
    ),
    (
        "finalgather_accuracy",
        "tests/fixtures/mi_controls/finalgather_accuracy.mi:4:22: error: finalgather accuracy must be at least 1 ray, found 0",
    ),
    (
        "photon_trace_depth",
        "tests/fixtures/mi_controls/photon_trace_depth.mi:4:14: error: expected depth after photon trace, found a number",
    ),
    (
        "globillum_radius",
        "tests/fixtures/mi_controls/globillum_radius.mi:4:24: error: the globillum accuracy radius must be ≥ 0, found -1",
    ),
];

#[test]
fn malformed_controls_give_exact_located_messages() {
    let mut names: Vec<String> = std::fs::read_dir(dir("tests/fixtures/mi_controls"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .collect();
    names.sort();
    assert_eq!(names.len(), MALFORMED.len(), "one expectation per fixture");
    for (stem, expected) in MALFORMED {
        let shown = Path::new("tests/fixtures/mi_controls").join(format!("{stem}.mi"));
        let got = match load_scene(&shown) {
            Ok(_) => "ok".to_string(),
            Err(e) => e.to_string(),
        };
        assert_eq!(got.trim_end(), *expected, "{stem}");
    }
}

/// mental ray's default is `face both` (seed 000: "The default is face both"): an options
/// block without `face` gives two-sided shading, `face front` one-sided with the back faces
/// left out of the rays (`Cull`, seed 000: "with face front, the back side would not be
/// visible").
#[test]
fn face_defaults_to_both_as_in_mental_ray() {
    for (statement, want) in [
        ("", FaceDesc::Both),
        ("face both\n", FaceDesc::Both),
        ("face front\n", FaceDesc::Cull),
    ] {
        let text = fixture_text(&format!("caustic on\n{statement}"));
        let read = read_mi(Path::new("face.mi"), text.as_bytes()).unwrap();
        assert_eq!(read.desc.options.unwrap().face, want, "{statement:?}");
    }
}

/// The physics library's photon shaders of `dgs_material` and `dielectric_material` scatter
/// photons as their materials scatter light — what the photon pass does with every BSDF — so
/// the seed's caustics scene reads them without a warning; another photon shader is still
/// reported, at the shader's name.
#[test]
fn material_photon_twins_map_and_other_photon_shaders_warn() {
    let path = dir("assets/seeds/mi/caustics.mi");
    let text = std::fs::read_to_string(&path).unwrap();
    let photon_warnings = |text: &str| -> Vec<String> {
        let read = read_mi(Path::new("caustics.mi"), text.as_bytes()).unwrap();
        read.warnings
            .iter()
            .filter(|w| w.problem.message.contains("photon shader"))
            .map(|w| {
                format!(
                    "{}:{}: {}",
                    w.problem.pos.line, w.problem.pos.column, w.problem.message
                )
            })
            .collect()
    };
    assert_eq!(photon_warnings(&text), Vec::<String>::new());
    let other = text.replace(
        "photon \"dgs_material_photon\" ()",
        "photon \"mib_photon_basic\" ()",
    );
    assert_eq!(
        photon_warnings(&other),
        ["73:8: photon shader \"mib_photon_basic\" is read but not yet mapped"]
    );
}

//! Replays the fuzz corpus (`fuzz/corpus/`) through the same checks as the fuzz targets, so
//! every input the fuzzers found interesting stays handled on the stable toolchain too.

use std::path::{Path, PathBuf};

fn corpus(target: &str) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fuzz/corpus")
        .join(target);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    files.sort();
    assert!(!files.is_empty(), "empty corpus {}", dir.display());
    files
}

#[test]
fn scene_corpus_loads_or_reports_located_errors() {
    for path in corpus("scene_ron") {
        let bytes = std::fs::read(&path).unwrap();
        let Ok(text) = std::str::from_utf8(&bytes) else {
            continue;
        };
        if let Err(errors) = stagelight::scene::load_scene_str(text, Path::new("fuzz.ron")) {
            assert!(!errors.0.is_empty(), "{}", path.display());
            for d in &errors.0 {
                assert!(d.line >= 1 && d.column >= 1, "{}: {d}", path.display());
            }
        }
    }
}

#[test]
fn obj_corpus_parses_to_checked_meshes_or_errors() {
    for path in corpus("obj_text") {
        let bytes = std::fs::read(&path).unwrap();
        if let Ok(mesh) = stagelight::scene::parse_obj_bytes(&bytes) {
            let n = mesh.positions.len() as u32;
            assert!(
                mesh.triangles.iter().all(|t| t.iter().all(|&i| i < n)),
                "{}",
                path.display()
            );
            assert!(mesh.positions.iter().all(|p| p.is_finite()));
        }
    }
}

#[test]
fn mtl_corpus_parses_to_materials_or_located_errors() {
    use stagelight::scene::mesh_files::{mtl, Location, MeshFileError};
    for path in corpus("mtl") {
        let bytes = std::fs::read(&path).unwrap();
        match mtl::parse(&bytes) {
            Ok(materials) => {
                for m in &materials {
                    assert!(m.opacity.is_none_or(|d| (0.0..=1.0).contains(&d)));
                    assert!(m.ior.is_none_or(|n| n > 0.0));
                }
            }
            Err(e) => assert!(
                matches!(e, MeshFileError::Parse { at: Location::Text { line, column }, .. } if line >= 1 && column >= 1),
                "{}: {e:?}",
                path.display()
            ),
        }
    }
}

#[test]
fn photon_map_corpus_decodes_to_valid_trees_or_errors() {
    let mut decoded = 0;
    for path in corpus("photon_map") {
        let bytes = std::fs::read(&path).unwrap();
        if let Ok(maps) = stagelight::photon::file::decode(&bytes) {
            decoded += 1;
            for stored in [&maps.caustics, &maps.global].into_iter().flatten() {
                for map in std::iter::once(&stored.map).chain(&stored.later) {
                    assert!(map.axes().iter().all(|&a| a < 3), "{}", path.display());
                }
            }
            assert_eq!(stagelight::photon::file::encode(&maps), bytes);
        }
    }
    assert_eq!(decoded, 1, "only valid.pmap decodes");
}

/// The PNG corpus decodes to consistent images or errors, as the `png` fuzz target checks;
/// the hand-made files decode to their known samples (bit depths below 8, palettes and
/// `tRNS` expanded; 16-bit samples read big-endian) and the damaged ones are errors.
#[test]
fn png_corpus_decodes_to_consistent_images_or_errors() {
    use stagelight::image_io::png_codec::{decode_png, Samples};
    for path in corpus("png") {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let decoded = decode_png(&std::fs::read(&path).unwrap());
        let Ok(img) = decoded else {
            assert!(
                name.starts_with("bricks_") || name.starts_with("bad_"),
                "{name}: {decoded:?}"
            );
            continue;
        };
        let len = match &img.samples {
            Samples::Eight(s) => s.len(),
            Samples::Sixteen(s) => s.len(),
        };
        assert_eq!(len, img.pixels() * img.channels, "{name}");
        for p in 0..img.pixels() {
            assert!(
                img.rgba(p).iter().all(|v| (0.0..=1.0).contains(v)),
                "{name}"
            );
        }
        match name.as_str() {
            "grey_1bit.png" => {
                assert_eq!((img.width, img.height, img.channels), (8, 2, 1));
                let bits = [1, 0, 1, 0, 0, 1, 0, 1, 0, 1, 0, 1, 1, 0, 1, 0].map(|b| b * 255);
                assert_eq!(img.samples, Samples::Eight(bits.to_vec()));
            }
            "palette_trns.png" => {
                assert_eq!((img.width, img.height, img.channels), (4, 2, 4));
                // Indices 0 1 2 3 / 3 2 1 0; tRNS makes index 0 clear, index 1 half.
                assert_eq!(img.rgba(0), [1.0, 0.0, 0.0, 0.0]);
                assert_eq!(img.rgba(1), [0.0, 1.0, 0.0, 128.0 / 255.0]);
                assert_eq!(img.rgba(4), [1.0, 1.0, 1.0, 1.0]);
            }
            "grey_alpha_16.png" => {
                assert_eq!((img.width, img.height, img.channels), (2, 2, 2));
                let want = [0x1234, 0xffff, 0, 0x8000, 0xffff, 1, 0xabcd, 0];
                assert_eq!(img.samples, Samples::Sixteen(want.to_vec()));
            }
            _ => {}
        }
    }
}

/// The EXR corpus decodes to width × height pixels or errors, as the `exr` fuzz target checks;
/// the file claiming 60000² pixels is refused from its headers.
#[test]
fn exr_corpus_decodes_to_consistent_images_or_errors() {
    use stagelight::shading::texture::image::decode_exr;
    for path in corpus("exr") {
        let decoded = decode_exr(&std::fs::read(&path).unwrap());
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        match (name.as_str(), decoded) {
            ("claims_60000x60000.exr", Err(e)) => {
                assert!(e.starts_with("a layer of 60000×60000 pixels"), "{e}")
            }
            ("tiny_4x4_zip.exr", Ok((w, h, ..))) => assert_eq!((w, h), (4, 4)),
            (_, Ok((w, h, texels, alpha))) => {
                assert_eq!(texels.len(), w as usize * h as usize, "{name}");
                assert!(alpha.is_empty() || alpha.len() == texels.len(), "{name}");
            }
            (_, Err(_)) => {}
        }
    }
}

/// The `part_file` target's checks: a part file that decodes (as a render or a bake part)
/// encodes again and decodes to the same header.
#[test]
fn part_file_corpus_decodes_and_round_trips_or_is_refused() {
    use stagelight::farm::{bake_part_file, part_file};
    let mut decoded = 0;
    for path in corpus("part_file") {
        let bytes = std::fs::read(&path).unwrap();
        if let Ok(part) = part_file::decode(&bytes) {
            let back = part_file::decode(&part_file::encode(&part).unwrap()).unwrap();
            assert_eq!(back.header, part.header, "{}", path.display());
            decoded += 1;
        }
        if let Ok(part) = bake_part_file::decode(&bytes) {
            let back = bake_part_file::decode(&bake_part_file::encode(&part).unwrap()).unwrap();
            assert_eq!(back.header, part.header, "{}", path.display());
            decoded += 1;
        }
    }
    assert!(
        decoded >= 2,
        "the corpus holds a render part and a bake part"
    );
}

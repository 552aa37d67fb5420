//! Merging part files into the frame buffers the single-machine render produces, bit for
//! bit: the parts must be one complete set (same scene, settings, seed, split and count,
//! each part exactly once); then the exact sums add, the counts add, and the centre-sample
//! passes come from the part that owns each pixel. The pixel values are derived exactly as
//! `shade` derives them ([`pixel_value`], [`pixel_alpha`]).

use std::path::{Path, PathBuf};

use super::part::{Part, Split};
use super::part_file::{PartFile, PartHeader, PartPixels};
use crate::adaptive::{pixel_alpha, pixel_value};
use crate::exact_sum::ExactSum;
use crate::framebuffer::FrameBuffers;
use glam::Vec3;

/// A part file that was read, with the path it came from.
pub struct LoadedPart {
    /// Where it was read from (for messages).
    pub path: PathBuf,
    /// Its content.
    pub file: PartFile,
}

/// The largest part file read (a part of a 16k × 16k image is well below it).
pub const MAX_PART_BYTES: u64 = 64 << 30;

/// Reads and decodes part files; the first unreadable one is the error.
pub fn read_parts(paths: &[PathBuf]) -> Result<Vec<LoadedPart>, String> {
    let mut parts = Vec::with_capacity(paths.len());
    for path in paths {
        let size = std::fs::metadata(path)
            .map_err(|e| format!("cannot read part file {}: {e}", path.display()))?
            .len();
        if size > MAX_PART_BYTES {
            return Err(format!(
                "{} is {size} bytes, more than a part file can be ({MAX_PART_BYTES})",
                path.display()
            ));
        }
        let bytes = std::fs::read(path)
            .map_err(|e| format!("cannot read part file {}: {e}", path.display()))?;
        let file =
            super::part_file::decode(&bytes).map_err(|e| format!("{}: {e}", path.display()))?;
        parts.push(LoadedPart {
            path: path.clone(),
            file,
        });
    }
    Ok(parts)
}

/// Checks that `parts` are one complete set; the error names the offending files.
fn check_set(parts: &[LoadedPart]) -> Result<(), String> {
    let headers: Vec<(&Path, &PartHeader)> = parts
        .iter()
        .map(|p| (p.path.as_path(), &p.file.header))
        .collect();
    check_headers(&headers, "render")
}

/// Checks that the parts with these headers are one complete set of one `stagelight
/// <command> --part K/N` run (`command` is `render` or `bake`, for the help lines): same
/// scene, seed, split, count, settings and resolution, each part exactly once.
pub fn check_headers(parts: &[(&Path, &PartHeader)], command: &str) -> Result<(), String> {
    let Some(&(p0, h0)) = parts.first() else {
        return Err("no part files given".into());
    };
    let p0 = p0.display();
    for &(path, h) in &parts[1..] {
        let path = path.display();
        let differs = |what: &str, a: String, b: String| {
            Err(format!(
                "{path} and {p0} are parts of different {command}s: {what} {b} vs {a}\n  help: merge only the parts of one `stagelight {command} --part K/N` run"
            ))
        };
        if h.scene_hash != h0.scene_hash {
            return differs(
                "scene content",
                format!("{:016x} ({})", h0.scene_hash, h0.scene),
                format!("{:016x} ({})", h.scene_hash, h.scene),
            );
        }
        if h.seed != h0.seed {
            return differs("seed", h0.seed.to_string(), h.seed.to_string());
        }
        if h.part.split != h0.part.split {
            return differs("split", h0.part.split.to_string(), h.part.split.to_string());
        }
        if h.part.count != h0.part.count {
            return differs(
                "part count",
                h0.part.count.to_string(),
                h.part.count.to_string(),
            );
        }
        if h.settings_hash != h0.settings_hash {
            // The settings a part records are named; the rest only its hash covers.
            if let Some((what, a, b)) = h0.recorded.first_difference(h.recorded) {
                return differs(what, a, b);
            }
            if h.version != h0.version {
                return differs("stagelight version", h0.version.clone(), h.version.clone());
            }
            return differs(
                "render settings",
                format!("{:016x}{}", h0.settings_hash, unrecorded_settings(command)),
                format!("{:016x}", h.settings_hash),
            );
        }
        if (h.width, h.height) != (h0.width, h0.height) {
            return differs(
                "resolution",
                format!("{}×{}", h0.width, h0.height),
                format!("{}×{}", h.width, h.height),
            );
        }
    }
    let count = h0.part.count;
    let mut seen: Vec<Option<&Path>> = vec![None; count as usize];
    for &(path, h) in parts {
        let k = h.part.index;
        let slot = &mut seen[(k - 1) as usize];
        if let Some(other) = slot {
            return Err(format!(
                "part {k}/{count} is given twice: {} and {}\n  help: pass each part file once",
                other.display(),
                path.display()
            ));
        }
        *slot = Some(path);
    }
    let missing: Vec<u32> = (1..=count)
        .filter(|k| seen[(k - 1) as usize].is_none())
        .collect();
    if !missing.is_empty() {
        return Err(missing_parts(&missing, count, command));
    }
    Ok(())
}

/// What differs between parts whose settings hashes differ although their scene, seed,
/// recorded settings and stagelight version agree: what `command` can override that the
/// part files keep only in the hash.
fn unrecorded_settings(command: &str) -> &'static str {
    if command == "render" {
        " (scene, seed, integrator and disabled features agree, so the parts were rendered with different `--spp` or `--diagnostic`, which a part file records only in this hash)"
    } else {
        " (scene, seed, integrator and disabled features agree, and `bake` overrides nothing else: the parts were baked by different builds of this stagelight version)"
    }
}

/// The refusal of a set without the parts `missing` (in order) of `count`, naming them in
/// the re-run command and as array indices.
fn missing_parts(missing: &[u32], count: u32, command: &str) -> String {
    const SHOWN: usize = 10;
    let list = |sep: &str, form: &dyn Fn(u32) -> String| {
        let shown: Vec<String> = missing.iter().take(SHOWN).map(|&k| form(k)).collect();
        let more = if missing.len() > SHOWN {
            format!("{sep}…")
        } else {
            String::new()
        };
        format!("{}{more}", shown.join(sep))
    };
    let parts = list(", ", &|k| format!("{k}/{count}"));
    if let [k] = missing {
        return format!(
            "missing part {parts}\n  help: re-run `stagelight {command} --part {k}/{count}` (or resubmit array index {k})"
        );
    }
    let total = if missing.len() > SHOWN {
        format!(" ({} parts)", missing.len())
    } else {
        String::new()
    };
    let numbers = |sep: &str| list(sep, &|k| k.to_string());
    format!(
        "missing parts {parts}{total}\n  help: re-run `stagelight {command} --part K/{count}` for K = {} (or resubmit array indices {})",
        numbers(", "),
        numbers(",")
    )
}

/// Whether pixel `i` of a part holds nothing, as every pixel outside a tile part's own
/// tiles must (its samples, counts and centre-sample passes are those of no sample).
fn is_empty(px: &PartPixels, i: usize) -> bool {
    px.sums[i].iter().all(|s| *s == ExactSum::default())
        && px.taken[i] == 0
        && px.covered[i] == 0
        && px.dropped[i] == 0
        && px.depth[i] == f32::INFINITY
        && px.normal[i] == Vec3::ZERO
        && px.object_id[i] == 0
        && px.material_id[i] == 0
        && px
            .components
            .as_ref()
            .is_none_or(|c| c[i].iter().all(|v| *v == Vec3::ZERO))
        && px
            .environment
            .as_ref()
            .is_none_or(|e| e[i].iter().all(|s| *s == ExactSum::default()))
}

/// Merges a complete set of parts into frame buffers (see the module header); a tile part
/// with samples outside its own tiles is refused as damaged.
pub fn merge(parts: &[LoadedPart]) -> Result<FrameBuffers, String> {
    check_set(parts)?;
    let h0 = &parts[0].file.header;
    let (width, height) = (h0.width as usize, h0.height as usize);
    let split = h0.part.split;
    let count = h0.part.count;
    let n = width * height;
    let mut total = PartPixels::new(n);
    // Component passes come only from tile parts, each pixel from its owner.
    if parts.iter().all(|p| p.file.pixels.components.is_some()) {
        total.components = Some(vec![[Vec3::ZERO; 6]; n]);
    }
    // The environment's share: the exact sums add like the beauty's.
    if parts.iter().all(|p| p.file.pixels.environment.is_some()) {
        total.environment = Some(vec![[ExactSum::default(); 3]; n]);
    }
    for p in parts {
        let px = &p.file.pixels;
        let k = p.file.header.part.index;
        for i in 0..n {
            let owner = Part::owner_of(split, count, i % width, i / width, width);
            if split == Split::Tiles && owner != k {
                if !is_empty(px, i) {
                    return Err(format!(
                        "{}: damaged part file (pixel ({}, {}) holds samples, but it belongs to part {owner}/{count}, not to this part {k}/{count})",
                        p.path.display(),
                        i % width,
                        i / width
                    ));
                }
                continue;
            }
            for c in 0..3 {
                total.sums[i][c].merge(&px.sums[i][c]);
            }
            total.taken[i] += px.taken[i];
            total.covered[i] += px.covered[i];
            total.dropped[i] += px.dropped[i];
            if let (Some(t), Some(e)) = (&mut total.environment, &px.environment) {
                for c in 0..3 {
                    t[i][c].merge(&e[i][c]);
                }
            }
            if owner == k {
                total.depth[i] = px.depth[i];
                total.normal[i] = px.normal[i];
                total.object_id[i] = px.object_id[i];
                total.material_id[i] = px.material_id[i];
                if let (Some(t), Some(c)) = (&mut total.components, &px.components) {
                    t[i] = c[i];
                }
            }
        }
    }
    let mut fb = FrameBuffers::new(h0.width, h0.height);
    for i in 0..n {
        let taken = total.taken[i];
        fb.beauty[i] = pixel_value(&total.sums[i], taken);
        fb.alpha[i] = pixel_alpha(total.covered[i], taken);
        fb.depth[i] = total.depth[i];
        fb.normal[i] = total.normal[i];
        fb.object_id[i] = total.object_id[i];
        fb.material_id[i] = total.material_id[i];
        fb.samples[i] = taken;
    }
    fb.components = total.components;
    fb.environment = total.environment.map(|sums| {
        (sums.iter().zip(&total.taken))
            .map(|(s, &taken)| pixel_value(s, taken))
            .collect()
    });
    Ok(fb)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Part `index` of 2 of a 32×16 image (tile 1 is part 1's, tile 2 part 2's), each
    /// owned pixel with one sample.
    fn tile_part(index: u32) -> LoadedPart {
        let (width, height) = (32u32, 16u32);
        let mut pixels = PartPixels::new((width * height) as usize);
        for i in 0..pixels.taken.len() {
            if Part::owner_of(Split::Tiles, 2, i % 32, i / 32, 32) == index {
                pixels.sums[i][0].add(0.5);
                pixels.taken[i] = 1;
            }
        }
        LoadedPart {
            path: format!("p{index}.exr").into(),
            file: PartFile {
                header: PartHeader::for_tests(index, width, height),
                pixels,
            },
        }
    }

    #[test]
    fn a_tile_part_with_samples_outside_its_tiles_is_refused() {
        let whole = merge(&[tile_part(1), tile_part(2)]).unwrap();
        assert!(whole.samples.iter().all(|&s| s == 1));
        // Part 2's pixels under part 1's label (and the other way round).
        let mut a = tile_part(2);
        a.file.header.part.index = 1;
        let mut b = tile_part(1);
        b.file.header.part.index = 2;
        assert_eq!(
            merge(&[a, b]).err().unwrap(),
            "p2.exr: damaged part file (pixel (16, 0) holds samples, but it belongs to part 2/2, not to this part 1/2)"
        );
        // A centre-sample pass alone counts too.
        let mut a = tile_part(1);
        a.file.pixels.depth[31] = 1.0;
        assert_eq!(
            merge(&[a, tile_part(2)]).err().unwrap(),
            "p1.exr: damaged part file (pixel (31, 0) holds samples, but it belongs to part 2/2, not to this part 1/2)"
        );
    }

    #[test]
    fn missing_parts_are_named_in_the_rerun_command() {
        assert_eq!(
            missing_parts(&[3], 5, "render"),
            "missing part 3/5\n  help: re-run `stagelight render --part 3/5` (or resubmit array index 3)"
        );
        assert_eq!(
            missing_parts(&[2, 4], 5, "bake"),
            "missing parts 2/5, 4/5\n  help: re-run `stagelight bake --part K/5` for K = 2, 4 (or resubmit array indices 2,4)"
        );
        let many: Vec<u32> = (1..=12).collect();
        let e = missing_parts(&many, 12, "render");
        assert!(
            e.starts_with("missing parts 1/12, 2/12, 3/12, 4/12, 5/12, 6/12, 7/12, 8/12, 9/12, 10/12, … (12 parts)\n"),
            "{e}"
        );
        assert!(
            e.ends_with("for K = 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, … (or resubmit array indices 1,2,3,4,5,6,7,8,9,10,…)"),
            "{e}"
        );
    }

    #[test]
    fn parts_of_different_settings_name_what_differs() {
        let refusal = |edit: &dyn Fn(&mut PartHeader), command| {
            let a = PartHeader::for_tests(1, 4, 4);
            let mut b = PartHeader::for_tests(2, 4, 4);
            b.settings_hash = 3;
            edit(&mut b);
            let parts = [(Path::new("p1.exr"), &a), (Path::new("p2.exr"), &b)];
            check_headers(&parts, command).unwrap_err()
        };
        let help = "\n  help: merge only the parts of one `stagelight render --part K/N` run";
        assert_eq!(
            refusal(
                &|h| h.recorded.integrator = crate::settings::Integrator::Path,
                "render"
            ),
            format!(
                "p2.exr and p1.exr are parts of different renders: integrator path vs direct{help}"
            )
        );
        assert_eq!(
            refusal(
                &|h| h.recorded.disabled = crate::features::Features::parse_list("lens").unwrap(),
                "render"
            ),
            format!("p2.exr and p1.exr are parts of different renders: disabled features lens vs none{help}")
        );
        assert_eq!(
            refusal(&|h| h.version = "1".into(), "render"),
            format!(
                "p2.exr and p1.exr are parts of different renders: stagelight version 1 vs 0{help}"
            )
        );
        assert_eq!(
            refusal(&|_| {}, "render"),
            format!("p2.exr and p1.exr are parts of different renders: render settings 0000000000000003 vs 0000000000000002 (scene, seed, integrator and disabled features agree, so the parts were rendered with different `--spp` or `--diagnostic`, which a part file records only in this hash){help}")
        );
        assert_eq!(
            refusal(&|_| {}, "bake"),
            "p2.exr and p1.exr are parts of different bakes: render settings 0000000000000003 vs 0000000000000002 (scene, seed, integrator and disabled features agree, and `bake` overrides nothing else: the parts were baked by different builds of this stagelight version)\n  help: merge only the parts of one `stagelight bake --part K/N` run"
        );
    }
}

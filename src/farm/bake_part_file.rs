//! The bake part file: one `bake --part K/N` run's texels as a multi-layer OpenEXR file.
//! Layer `r.m` holds image `m` of request `r` before dilation (`R`, `G`, `B` as f32, `valid`
//! as u32 0/1); the first layer carries the metadata shared with render parts (format,
//! version, scene, content and settings hashes, recorded settings, seed, K/N) plus, per request, its name,
//! image count, rays and invalid texels, and a checksum of every other entry and all texel
//! data — as `key value` lines of one text attribute (`super::exr_meta`).

use exr::prelude::*;
use glam::Vec3;

use super::bake_part::{BakePartFile, BakePartRequest, LoadedBakePart};
use super::part::Split;
use super::part_file::{hex, shared_entries, unhex, Entries, PartHeader, CHECKSUM};
use crate::bake::TexelImage;
use crate::hash::Fnv64;

/// The `format` entry of a bake part's metadata.
pub const FORMAT: &str = "stagelight bake part 3";

/// Earlier formats, whose checksum covered only the texel data: recognised as bake parts
/// and refused with a message that asks for the parts to be baked again.
pub const OLDER_FORMATS: &[&str] = &["stagelight bake part 2", "stagelight bake part 1"];

/// FNV-1a over every request's counters and texels (what the `checksum` entry covers
/// besides the other entries).
fn payload_hash(requests: &[BakePartRequest]) -> u64 {
    let mut h = Fnv64::default();
    for r in requests {
        h.bytes(r.name.as_bytes());
        h.bytes(&r.rays.to_le_bytes());
        h.bytes(&r.invalid.to_le_bytes());
        for img in &r.images {
            h.bytes(&img.width.to_le_bytes());
            h.bytes(&img.height.to_le_bytes());
            for (t, v) in img.texels.iter().zip(&img.valid) {
                for c in t.to_array() {
                    h.bytes(&c.to_bits().to_le_bytes());
                }
                h.bytes(&[u8::from(*v)]);
            }
        }
    }
    h.finish()
}

/// Encodes a bake part file. Fails when no request has an image (nothing to store).
pub fn encode(part: &BakePartFile) -> std::result::Result<Vec<u8>, String> {
    let h = &part.header;
    let mut layers: Vec<Layer<AnyChannels<FlatSamples>>> = Vec::new();
    for (r, request) in part.requests.iter().enumerate() {
        for (m, img) in request.images.iter().enumerate() {
            let mut channels: SmallVec<[AnyChannel<FlatSamples>; 4]> = [0usize, 1, 2]
                .into_iter()
                .map(|c| {
                    AnyChannel::new(
                        ["R", "G", "B"][c],
                        FlatSamples::F32(img.texels.iter().map(|t| t[c]).collect()),
                    )
                })
                .collect();
            channels.push(AnyChannel::new(
                "valid",
                FlatSamples::U32(img.valid.iter().map(|&v| u32::from(v)).collect()),
            ));
            let mut attributes = LayerAttributes::named(format!("{r}.{m}").as_str());
            if layers.is_empty() {
                header_attributes(&mut attributes, h, &part.requests);
            }
            layers.push(Layer::new(
                (img.width as usize, img.height as usize),
                attributes,
                Encoding::SMALL_LOSSLESS,
                AnyChannels::sort(channels),
            ));
        }
    }
    let Some(first) = layers.first() else {
        return Err("a bake part needs at least one baked image".into());
    };
    let bounds = IntegerBounds::new((0, 0), first.size);
    let mut cursor = std::io::Cursor::new(Vec::new());
    Image::from_layers(ImageAttributes::new(bounds), layers)
        .write()
        .non_parallel()
        .to_buffered(&mut cursor)
        .map_err(|e| e.to_string())?;
    Ok(cursor.into_inner())
}

/// The metadata (all ASCII: numbers, hex, names of our own), in one attribute.
fn header_attributes(
    attributes: &mut LayerAttributes,
    h: &PartHeader,
    requests: &[BakePartRequest],
) {
    let mut pairs = entries_of(h, requests);
    let checksum = super::exr_meta::checksum(&pairs, payload_hash(requests));
    pairs.push((CHECKSUM.into(), format!("{checksum:016x}")));
    super::exr_meta::put(attributes, &pairs);
}

/// The metadata entries of a bake part without the checksum, in order.
fn entries_of(h: &PartHeader, requests: &[BakePartRequest]) -> Vec<(String, String)> {
    let mut pairs = shared_entries(FORMAT, h);
    pairs.push(("requests".into(), requests.len().to_string()));
    for (r, request) in requests.iter().enumerate() {
        pairs.push((
            format!("request.{r}"),
            format!(
                "{} {} {} {}",
                hex(request.name.as_bytes()),
                request.images.len(),
                request.rays,
                request.invalid
            ),
        ));
    }
    pairs
}

/// Whether this EXR metadata names a bake part format (this one or an older one, which the
/// decoder refuses with its own message).
fn names_bake_format(meta: &exr::meta::MetaData) -> bool {
    meta.headers
        .first()
        .and_then(super::exr_meta::read_header)
        .is_some_and(|m| {
            m.get("format")
                .is_some_and(|f| f == FORMAT || OLDER_FORMATS.contains(&f.as_str()))
        })
}

/// Whether `bytes` are a bake part file (an EXR whose metadata names this format).
pub fn is_bake_part(bytes: &[u8]) -> bool {
    exr::meta::MetaData::read_from_buffered(std::io::Cursor::new(bytes), false)
        .is_ok_and(|meta| names_bake_format(&meta))
}

/// Whether the file at `path` is a bake part file (reads only its header); `stagelight
/// merge` uses it to tell bake parts from render parts.
pub fn is_bake_part_file(path: &std::path::Path) -> bool {
    exr::meta::MetaData::read_from_file(path, false).is_ok_and(|meta| names_bake_format(&meta))
}

/// Reads and decodes bake part files; the first unreadable one is the error.
pub fn read_parts(
    paths: &[std::path::PathBuf],
) -> std::result::Result<Vec<LoadedBakePart>, String> {
    let mut parts = Vec::with_capacity(paths.len());
    for path in paths {
        let size = std::fs::metadata(path)
            .map_err(|e| format!("cannot read part file {}: {e}", path.display()))?
            .len();
        if size > super::merge::MAX_PART_BYTES {
            return Err(format!(
                "{} is {size} bytes, more than a part file can be ({})",
                path.display(),
                super::merge::MAX_PART_BYTES
            ));
        }
        let bytes = std::fs::read(path)
            .map_err(|e| format!("cannot read part file {}: {e}", path.display()))?;
        let file = decode(&bytes).map_err(|e| format!("{}: {e}", path.display()))?;
        parts.push(LoadedBakePart {
            path: path.clone(),
            file,
        });
    }
    Ok(parts)
}

/// The help for a bake part file that cannot be decoded (cut short by a part killed while
/// writing it, or by a full disk).
const UNREADABLE_HELP: &str =
    "help: bake this part again (`stagelight bake --part K/N`); a part file is whole once its bake has exited with status 0";

/// Why a file that is not an EXR file (a scene, a PNG) is no bake part file.
const NOT_EXR: &str =
    "not a bake part file: it is not an EXR file\n  help: merge the EXR part files that `stagelight bake --part K/N` writes";

/// Decodes a bake part file; the error says what is wrong with it (the caller names the file).
pub fn decode(bytes: &[u8]) -> std::result::Result<BakePartFile, String> {
    use crate::image_io::exr_limits;
    if !crate::image_io::exr_magic::could_be_exr(bytes) {
        return Err(NOT_EXR.into());
    }
    exr_limits::check_bytes(bytes, exr_limits::MAX_PART_SAMPLES)?;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .all_layers()
        .all_attributes()
        .non_parallel()
        .from_buffered(std::io::Cursor::new(bytes))
        .map_err(|e| {
            format!("not a readable EXR file ({e}); it may be truncated\n  {UNREADABLE_HELP}")
        })?;
    let layers = &image.layer_data;
    let not_part = |why: &str| {
        format!("not a stagelight bake part file ({why})\n  help: merge the EXR part files that `stagelight bake --part K/N` writes")
    };
    let first = layers.first().ok_or_else(|| not_part("no layers"))?;
    let attrs = super::exr_meta::read(&first.attributes)
        .ok_or_else(|| not_part("no `stagelight` attribute"))?;
    let entries = Entries::new(attrs, "bake part file");
    let header = entries.header(FORMAT, OLDER_FORMATS, "bake", Split::Tiles, 0, 0)?;
    let get = |key: &str| entries.get(key);
    let bad = |key: &str| entries.bad(key);
    let count: usize = get("requests")?.parse().map_err(|_| bad("requests"))?;
    if count > layers.len() {
        return Err(bad("requests"));
    }
    let mut requests = Vec::with_capacity(count);
    for r in 0..count {
        let key = format!("request.{r}");
        let value = get(&key)?;
        let fields: Vec<&str> = value.split(' ').collect();
        let [name, images, rays, invalid] = fields[..] else {
            return Err(bad(&key));
        };
        let name = unhex(name)
            .and_then(|b| String::from_utf8(b).ok())
            .ok_or_else(|| bad(&key))?;
        let images: usize = images.parse().map_err(|_| bad(&key))?;
        let images = (0..images)
            .map(|m| layer_image(layers, &format!("{r}.{m}")))
            .collect::<std::result::Result<Vec<_>, _>>()?;
        requests.push(BakePartRequest {
            name,
            images,
            rays: rays.parse().map_err(|_| bad(&key))?,
            invalid: invalid.parse().map_err(|_| bad(&key))?,
        });
    }
    entries.check_checksum(&entries_of(&header, &requests), payload_hash(&requests))?;
    Ok(BakePartFile { header, requests })
}

/// The image stored in the layer named `name`.
fn layer_image(
    layers: &[Layer<AnyChannels<FlatSamples>>],
    name: &str,
) -> std::result::Result<TexelImage, String> {
    let layer = layers
        .iter()
        .find(|l| l.attributes.layer_name.as_ref().is_some_and(|n| n == name))
        .ok_or_else(|| format!("damaged bake part file (no layer `{name}`)"))?;
    let n = layer.size.area();
    let find = |channel: &str| {
        layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name.to_string() == channel)
            .map(|c| &c.sample_data)
    };
    let damaged = || format!("damaged bake part file (layer `{name}` lacks its channels)");
    let f32s = |channel: &str| match find(channel) {
        Some(FlatSamples::F32(v)) if v.len() == n => Ok(v),
        _ => Err(damaged()),
    };
    let (r, g, b) = (f32s("R")?, f32s("G")?, f32s("B")?);
    let Some(FlatSamples::U32(valid)) = find("valid") else {
        return Err(damaged());
    };
    if valid.len() != n {
        return Err(damaged());
    }
    Ok(TexelImage {
        width: layer.size.width() as u32,
        height: layer.size.height() as u32,
        texels: (0..n).map(|i| Vec3::new(r[i], g[i], b[i])).collect(),
        valid: valid.iter().map(|&v| v != 0).collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::farm::part::Part;

    fn sample() -> BakePartFile {
        let mut a = TexelImage::new(3, 2);
        a.texels[4] = Vec3::new(0.25, -1.0, 1e-30);
        a.valid[4] = true;
        let b = TexelImage::new(1, 5);
        BakePartFile {
            header: PartHeader {
                version: "0.1.0".into(),
                scene: "scènes/bake.ron".into(),
                scene_hash: 0xfeed,
                settings_hash: 3,
                recorded: crate::farm::recorded_settings::RecordedSettings {
                    disabled: crate::features::Features::NONE,
                    integrator: crate::settings::Integrator::Path,
                },
                seed: 9,
                part: Part {
                    index: 2,
                    count: 3,
                    split: Split::Tiles,
                },
                width: 0,
                height: 0,
            },
            requests: vec![
                BakePartRequest {
                    name: "floor/1".into(),
                    images: vec![a.clone(), a],
                    rays: 77,
                    invalid: 1,
                },
                BakePartRequest {
                    name: "rock".into(),
                    images: vec![b],
                    rays: 0,
                    invalid: 0,
                },
            ],
        }
    }

    #[test]
    fn round_trips_every_field_and_is_recognised() {
        let part = sample();
        let bytes = encode(&part).unwrap();
        assert!(is_bake_part(&bytes));
        assert_eq!(decode(&bytes).unwrap(), part);
    }

    #[test]
    fn the_checksum_covers_the_part_number_seed_and_request_counters() {
        let bytes = encode(&sample()).unwrap();
        let edited = crate::farm::part_file::tests::edited;
        for (from, to) in [
            ("\npart 2/3\n", "\npart 3/3\n"),
            ("\nseed 9\n", "\nseed 8\n"),
            ("\nintegrator path\n", "\nintegrator ptah\n"),
            (" 77 1\n", " 78 1\n"),
        ] {
            let e = decode(&edited(&bytes, from, to)).unwrap_err();
            let expected = if from.contains("integrator") {
                "damaged bake part file (entry `integrator` is malformed)"
            } else {
                "damaged bake part file (its metadata or data do not match its checksum)"
            };
            assert_eq!(e, expected, "{from:?} → {to:?}");
        }
    }

    #[test]
    fn files_of_an_older_format_are_recognised_and_refused_with_the_rebake_help() {
        let bytes = encode(&sample()).unwrap();
        let old = crate::farm::part_file::tests::edited(
            &bytes,
            "format stagelight bake part 3",
            "format stagelight bake part 2",
        );
        assert!(is_bake_part(&old));
        assert_eq!(
            decode(&old).unwrap_err(),
            "bake part file of the older format \"stagelight bake part 2\", whose checksum leaves out its part number and settings (this stagelight writes \"stagelight bake part 3\")\n  help: bake the parts again with this stagelight (`stagelight bake --part K/N`)"
        );
    }

    #[test]
    fn truncated_and_foreign_files_are_refused() {
        let bytes = encode(&sample()).unwrap();
        let e = decode(&bytes[..bytes.len() - 40]).unwrap_err();
        assert!(e.contains("truncated") || e.starts_with("damaged"), "{e}");
        assert!(!is_bake_part(b"not an exr"));
        assert_eq!(decode(b"not an exr").unwrap_err(), NOT_EXR);
        assert_eq!(decode(b"\x89PNG\r\n\x1a\n").unwrap_err(), NOT_EXR);
        let e = decode(&bytes[..3]).unwrap_err();
        assert!(e.starts_with("not a readable EXR file"), "{e}");
    }
}

//! The part file: one farm part's results as an OpenEXR file that holds exactly what an
//! exact merge needs — per pixel the exact sample sums ([`ExactSum`] limbs as `u32` words),
//! the sample, coverage and dropped counts, the centre-sample passes and, when the camera
//! sees an environment, the exact sums of the samples that missed every surface — plus metadata
//! (format, stagelight version, scene, scene content hash, settings hash, the recorded
//! settings of `super::recorded_settings`, seed, part K/N, split) as `key value` lines of one
//! EXR text attribute (`super::exr_meta`), ending in a checksum of every other entry and the
//! pixel data that catches a damaged or edited file.

use std::collections::HashMap;

use exr::prelude::*;
use glam::Vec3;

use super::part::{Part, Split};
use super::recorded_settings::RecordedSettings;
use crate::exact_sum::{ExactSum, LIMBS};
use crate::hash::Fnv64;

/// The `format` entry of the metadata.
pub const FORMAT: &str = "stagelight part 5";

/// Earlier formats, whose checksum covered only the pixel data: refused with a message that
/// asks for the parts to be rendered again (their part number and settings could have been
/// edited unnoticed).
pub const OLDER_FORMATS: &[&str] = &["stagelight part 3", "stagelight part 2"];

/// The format before the environment's share was kept: refused with a message that asks
/// for the parts to be rendered again (a merge could not take the environment out of a
/// partly covered pixel's straight colour, [`PartPixels::environment`]).
pub const WITHOUT_ENVIRONMENT: &str = "stagelight part 4";

/// Everything about a part except its pixels.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PartHeader {
    /// stagelight version that wrote it.
    pub version: String,
    /// The scene path as the render was given it.
    pub scene: String,
    /// Hash of the scene's content (see `crate::farm::scene_hash`).
    pub scene_hash: u64,
    /// Hash of the effective render settings (scene options plus command-line overrides).
    pub settings_hash: u64,
    /// The settings the merge applies.
    pub recorded: RecordedSettings,
    /// The seed.
    pub seed: u64,
    /// Which part this is.
    pub part: Part,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

#[cfg(test)]
impl PartHeader {
    /// Part `index` of 2 (tiles) of a fixed scene and settings, `width`×`height`: the
    /// header the merge tests build their parts with.
    pub(crate) fn for_tests(index: u32, width: u32, height: u32) -> Self {
        Self {
            version: "0".into(),
            scene: "s.ron".into(),
            scene_hash: 1,
            settings_hash: 2,
            recorded: super::recorded_settings::RecordedSettings {
                disabled: crate::features::Features::NONE,
                integrator: crate::settings::Integrator::Direct,
            },
            seed: 0,
            part: super::part::Part {
                index,
                count: 2,
                split: super::part::Split::Tiles,
            },
            width,
            height,
        }
    }
}

/// Per-pixel results of one part (row-major, full image size; pixels the part does not
/// compute are zero).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PartPixels {
    /// Exact sums of the R, G, B samples.
    pub sums: Vec<[ExactSum; 3]>,
    /// Samples taken.
    pub taken: Vec<u32>,
    /// Samples whose camera ray hit something.
    pub covered: Vec<u32>,
    /// Non-finite samples dropped.
    pub dropped: Vec<u32>,
    /// Centre-sample depth.
    pub depth: Vec<f32>,
    /// Centre-sample normal.
    pub normal: Vec<Vec3>,
    /// Centre-sample object id.
    pub object_id: Vec<u32>,
    /// Centre-sample material id.
    pub material_id: Vec<u32>,
    /// Component-pass values (emission … volume, `Pass::COMPONENTS` order) of the pixels a
    /// tile part owns, when the camera asks for component passes.
    pub components: Option<Vec<[Vec3; 6]>>,
    /// Exact sums of the R, G, B radiance of the samples that missed every surface, when
    /// the camera sees an environment (`crate::framebuffer::PixelSums::environment`).
    pub environment: Option<Vec<[ExactSum; 3]>>,
}

impl PartPixels {
    /// All-zero pixels for `n` pixels (depth infinite).
    pub fn new(n: usize) -> Self {
        Self {
            sums: vec![[ExactSum::default(); 3]; n],
            taken: vec![0; n],
            covered: vec![0; n],
            dropped: vec![0; n],
            depth: vec![f32::INFINITY; n],
            normal: vec![Vec3::ZERO; n],
            object_id: vec![0; n],
            material_id: vec![0; n],
            components: None,
            environment: None,
        }
    }
}

/// The part channel of component `k`'s colour channel `c`.
fn component_channel(k: usize, c: usize) -> String {
    format!("component.{k}.{}", CHANNELS[c])
}

/// A part file's content.
#[derive(Debug, Clone, PartialEq)]
pub struct PartFile {
    /// Metadata.
    pub header: PartHeader,
    /// Results.
    pub pixels: PartPixels,
}

const CHANNELS: [&str; 3] = ["R", "G", "B"];

fn sum_channel(c: usize, word: usize) -> String {
    format!("sum.{}.{word:02}", CHANNELS[c])
}

/// The channel of word `word` of the environment sums' colour channel `c`.
fn environment_channel(c: usize, word: usize) -> String {
    format!("environment.{}.{word:02}", CHANNELS[c])
}

/// The channels `name(c, word)` holding the 32-bit words of exact sums `sums`.
fn sum_words(
    sums: &[[ExactSum; 3]],
    name: fn(usize, usize) -> String,
    out: &mut Vec<(String, Vec<u32>)>,
) {
    for c in 0..3 {
        for word in 0..2 * LIMBS {
            let values = sums
                .iter()
                .map(|s| {
                    let limb = s[c].limbs()[word / 2];
                    (limb >> (32 * (word % 2))) as u32
                })
                .collect();
            out.push((name(c, word), values));
        }
    }
}

/// The u32 channels of a part, by name, in a fixed order.
fn u32_channels(p: &PartPixels) -> Vec<(String, Vec<u32>)> {
    let mut out = Vec::new();
    sum_words(&p.sums, sum_channel, &mut out);
    if let Some(environment) = &p.environment {
        sum_words(environment, environment_channel, &mut out);
    }
    out.push(("taken".into(), p.taken.clone()));
    out.push(("covered".into(), p.covered.clone()));
    out.push(("dropped".into(), p.dropped.clone()));
    out.push(("id.object".into(), p.object_id.clone()));
    out.push(("id.material".into(), p.material_id.clone()));
    out
}

/// The f32 channels of a part, by name, in a fixed order.
fn f32_channels(p: &PartPixels) -> Vec<(String, Vec<f32>)> {
    vec![
        ("Z".into(), p.depth.clone()),
        ("N.X".into(), p.normal.iter().map(|n| n.x).collect()),
        ("N.Y".into(), p.normal.iter().map(|n| n.y).collect()),
        ("N.Z".into(), p.normal.iter().map(|n| n.z).collect()),
    ]
    .into_iter()
    .chain(p.components.iter().flat_map(|values| {
        (0..6).flat_map(move |k| {
            (0..3).map(move |c| {
                (
                    component_channel(k, c),
                    values.iter().map(|v| v[k][c]).collect(),
                )
            })
        })
    }))
    .collect()
}

/// FNV-1a over the image size and the pixel data in channel order (what the `checksum`
/// entry covers besides the other entries).
fn payload_hash(width: u32, height: u32, p: &PartPixels) -> u64 {
    let mut h = Fnv64::default();
    h.bytes(&width.to_le_bytes()).bytes(&height.to_le_bytes());
    for (name, values) in u32_channels(p) {
        h.bytes(name.as_bytes());
        for v in &values {
            h.bytes(&v.to_le_bytes());
        }
    }
    for (name, values) in f32_channels(p) {
        h.bytes(name.as_bytes());
        for v in &values {
            h.bytes(&v.to_bits().to_le_bytes());
        }
    }
    h.finish()
}

/// Lower-case hex of `bytes` (names and paths in the metadata stay ASCII).
pub(super) fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// The bytes of a [`hex`] string; `None` when it is not one.
pub(super) fn unhex(s: &str) -> Option<Vec<u8>> {
    if !s.len().is_multiple_of(2) {
        return None;
    }
    (0..s.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(s.get(i..i + 2)?, 16).ok())
        .collect()
}

/// The metadata entries of a part file (render or bake), with the messages that say which
/// entry is missing or malformed.
pub(super) struct Entries {
    map: HashMap<String, String>,
    /// `part file` or `bake part file`, for the messages.
    kind: &'static str,
}

impl Entries {
    /// The entries read from a file of `kind`.
    pub(super) fn new(map: HashMap<String, String>, kind: &'static str) -> Self {
        Self { map, kind }
    }

    /// The entry `key`.
    pub(super) fn get(&self, key: &str) -> std::result::Result<String, String> {
        self.map
            .get(key)
            .cloned()
            .ok_or_else(|| format!("damaged {} (no `{key}` entry)", self.kind))
    }

    /// The message for a malformed entry `key`.
    pub(super) fn bad(&self, key: &str) -> String {
        format!("damaged {} (entry `{key}` is malformed)", self.kind)
    }

    /// The entry `key` as a 64-bit hex number.
    pub(super) fn hex64(&self, key: &str) -> std::result::Result<u64, String> {
        u64::from_str_radix(&self.get(key)?, 16).map_err(|_| self.bad(key))
    }

    /// The header shared by render and bake parts, after checking the format is `format`
    /// (an older one of `older` is refused with the help to run `stagelight <command>
    /// --part K/N` again).
    pub(super) fn header(
        &self,
        format: &str,
        older: &[&str],
        command: &str,
        split: Split,
        width: u32,
        height: u32,
    ) -> std::result::Result<PartHeader, String> {
        let found = self.get("format")?;
        if older.contains(&found.as_str()) {
            return Err(format!(
                "{} of the older format \"{found}\", whose checksum leaves out its part number and settings (this stagelight writes \"{format}\")\n  help: {command} the parts again with this stagelight (`stagelight {command} --part K/N`)",
                self.kind
            ));
        }
        let kind = |f: &str| {
            if f.starts_with("stagelight bake part") {
                Some("bake")
            } else if f.starts_with("stagelight part") {
                Some("render")
            } else {
                None
            }
        };
        if let (Some(got), Some(want)) = (kind(&found), kind(format)) {
            if got != want {
                return Err(format!(
                    "a {got} part file, not a {want} part file like the first part\n  help: merge the parts of one render, or of one bake"
                ));
            }
        }
        if found != format {
            return Err(format!(
                "part file format \"{found}\" is not \"{format}\" (written by another stagelight version?)"
            ));
        }
        let recorded = RecordedSettings::parse(&self.get("disable")?, &self.get("integrator")?)
            .map_err(|key| self.bad(key))?;
        let scene = unhex(&self.get("scene")?)
            .and_then(|b| String::from_utf8(b).ok())
            .ok_or_else(|| self.bad("scene"))?;
        let number: super::part::PartNumber =
            self.get("part")?.parse().map_err(|_| self.bad("part"))?;
        Ok(PartHeader {
            version: self.get("version")?,
            scene,
            scene_hash: self.hex64("scene_hash")?,
            settings_hash: self.hex64("settings_hash")?,
            recorded,
            seed: self.get("seed")?.parse().map_err(|_| self.bad("seed"))?,
            part: Part {
                index: number.index,
                count: number.count,
                split,
            },
            width,
            height,
        })
    }

    /// Checks the `checksum` entry against `entries` (the file's other entries as its
    /// decoded content writes them) and the hash of its `data`.
    pub(super) fn check_checksum(
        &self,
        entries: &[(String, String)],
        data: u64,
    ) -> std::result::Result<(), String> {
        if self.hex64(CHECKSUM)? != super::exr_meta::checksum(entries, data) {
            return Err(format!(
                "damaged {} (its metadata or data do not match its checksum)",
                self.kind
            ));
        }
        Ok(())
    }
}

/// The key of the checksum entry, the last one.
pub(super) const CHECKSUM: &str = "checksum";

/// The metadata entries shared by render and bake parts, in order, from `format` through
/// `part` (without the checksum).
pub(super) fn shared_entries(format: &str, h: &PartHeader) -> Vec<(String, String)> {
    let mut pairs: Vec<(String, String)> = [
        ("format", format.to_string()),
        ("version", h.version.clone()),
        ("scene", hex(h.scene.as_bytes())),
        ("scene_hash", format!("{:016x}", h.scene_hash)),
        ("settings_hash", format!("{:016x}", h.settings_hash)),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v))
    .collect();
    pairs.extend(h.recorded.entries());
    pairs.extend([
        ("seed".into(), h.seed.to_string()),
        ("part".into(), format!("{}/{}", h.part.index, h.part.count)),
    ]);
    pairs
}

/// The metadata entries of a render part without the checksum, in order.
fn entries_of(h: &PartHeader) -> Vec<(String, String)> {
    let mut pairs = shared_entries(FORMAT, h);
    pairs.push(("split".into(), h.part.split.name().into()));
    pairs
}

/// Encodes a part file.
pub fn encode(part: &PartFile) -> std::result::Result<Vec<u8>, String> {
    let h = &part.header;
    let p = &part.pixels;
    let mut channels: SmallVec<[AnyChannel<FlatSamples>; 4]> = SmallVec::new();
    for (name, values) in u32_channels(p) {
        channels.push(AnyChannel::new(name.as_str(), FlatSamples::U32(values)));
    }
    for (name, values) in f32_channels(p) {
        channels.push(AnyChannel::new(name.as_str(), FlatSamples::F32(values)));
    }
    let mut attributes = LayerAttributes::default();
    let mut pairs = entries_of(h);
    let checksum = super::exr_meta::checksum(&pairs, payload_hash(h.width, h.height, p));
    pairs.push((CHECKSUM.into(), format!("{checksum:016x}")));
    super::exr_meta::put(&mut attributes, &pairs);
    let layer = Layer::new(
        (h.width as usize, h.height as usize),
        attributes,
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(channels),
    );
    let mut cursor = std::io::Cursor::new(Vec::new());
    Image::from_layer(layer)
        .write()
        .non_parallel()
        .to_buffered(&mut cursor)
        .map_err(|e| e.to_string())?;
    Ok(cursor.into_inner())
}

/// What to merge instead of a file that is no part file.
const PART_FILES_HELP: &str =
    "help: merge the EXR part files that `stagelight render --part K/N -o PART.exr` (or `stagelight bake --part K/N`) writes";

/// Why a file that is not an EXR file (a scene, a PNG) is no part file.
const NOT_EXR: &str =
    "not a part file: it is not an EXR file\n  help: merge the EXR part files that `stagelight render --part K/N -o PART.exr` (or `stagelight bake --part K/N`) writes";

/// The help for a part file that cannot be decoded (cut short by a part killed while
/// writing it, or by a full disk).
const UNREADABLE_HELP: &str =
    "help: render this part again (`stagelight render --part K/N -o PART.exr`); a part file is whole once its render has exited with status 0";

/// Decodes a part file; the error says what is wrong with it (the caller names the file).
pub fn decode(bytes: &[u8]) -> std::result::Result<PartFile, String> {
    use crate::image_io::exr_limits;
    if !crate::image_io::exr_magic::could_be_exr(bytes) {
        return Err(NOT_EXR.into());
    }
    exr_limits::check_bytes(bytes, exr_limits::MAX_PART_SAMPLES)?;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .non_parallel()
        .from_buffered(std::io::Cursor::new(bytes))
        .map_err(|e| {
            format!("not a readable EXR file ({e}); it may be truncated\n  {UNREADABLE_HELP}")
        })?;
    let layer = image.layer_data;
    let attrs = super::exr_meta::read(&layer.attributes).ok_or_else(|| {
        format!("not a stagelight part file (no `stagelight` attribute): an EXR image, not a part of a render\n  {PART_FILES_HELP}")
    })?;
    let entries = Entries::new(attrs, "part file");
    if entries.get("format")? == WITHOUT_ENVIRONMENT {
        return Err(format!(
            "part file of the older format \"{WITHOUT_ENVIRONMENT}\", which leaves out the environment's share of partly covered pixels (this stagelight writes \"{FORMAT}\")\n  help: render the parts again with this stagelight (`stagelight render --part K/N`)"
        ));
    }
    let size = layer.size;
    let mut header = entries.header(
        FORMAT,
        OLDER_FORMATS,
        "render",
        Split::Tiles,
        size.width() as u32,
        size.height() as u32,
    )?;
    header.part.split =
        Split::from_name(&entries.get("split")?).ok_or_else(|| entries.bad("split"))?;
    let n = size.area();
    let find = |name: &str| {
        layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name.to_string() == name)
            .map(|c| &c.sample_data)
            .ok_or_else(|| format!("damaged part file (no `{name}` channel)"))
    };
    let u32s = |name: &str| match find(name)? {
        FlatSamples::U32(v) if v.len() == n => Ok(v.clone()),
        _ => Err(format!(
            "damaged part file (channel `{name}` is not {n} u32 samples)"
        )),
    };
    let f32s = |name: &str| match find(name)? {
        FlatSamples::F32(v) if v.len() == n => Ok(v.clone()),
        _ => Err(format!(
            "damaged part file (channel `{name}` is not {n} f32 samples)"
        )),
    };
    let mut pixels = PartPixels::new(n);
    let read_sums = |name: fn(usize, usize) -> String, sums: &mut [[ExactSum; 3]]| {
        for c in 0..3 {
            let words: Vec<Vec<u32>> = (0..2 * LIMBS)
                .map(|w| u32s(&name(c, w)))
                .collect::<std::result::Result<_, _>>()?;
            for (i, s) in sums.iter_mut().enumerate() {
                let mut limbs = [0u64; LIMBS];
                for (l, limb) in limbs.iter_mut().enumerate() {
                    *limb = u64::from(words[2 * l][i]) | (u64::from(words[2 * l + 1][i]) << 32);
                }
                s[c] = ExactSum::from_limbs(limbs);
            }
        }
        Ok::<_, String>(())
    };
    read_sums(sum_channel, &mut pixels.sums)?;
    if find(&environment_channel(0, 0)).is_ok() {
        let mut environment = vec![[ExactSum::default(); 3]; n];
        read_sums(environment_channel, &mut environment)?;
        pixels.environment = Some(environment);
    }
    pixels.taken = u32s("taken")?;
    pixels.covered = u32s("covered")?;
    pixels.dropped = u32s("dropped")?;
    pixels.object_id = u32s("id.object")?;
    pixels.material_id = u32s("id.material")?;
    pixels.depth = f32s("Z")?;
    let (nx, ny, nz) = (f32s("N.X")?, f32s("N.Y")?, f32s("N.Z")?);
    pixels.normal = (0..n).map(|i| Vec3::new(nx[i], ny[i], nz[i])).collect();
    if find(&component_channel(0, 0)).is_ok() {
        let mut values = vec![[Vec3::ZERO; 6]; n];
        for k in 0..6 {
            for c in 0..3 {
                for (v, x) in values.iter_mut().zip(f32s(&component_channel(k, c))?) {
                    v[k][c] = x;
                }
            }
        }
        pixels.components = Some(values);
    }
    let data = payload_hash(header.width, header.height, &pixels);
    entries.check_checksum(&entries_of(&header), data)?;
    Ok(PartFile { header, pixels })
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    fn sample() -> PartFile {
        let mut pixels = PartPixels::new(6);
        pixels.sums[1][0].add(1.5);
        pixels.sums[4][2].add(-1e-30);
        pixels.taken[1] = 3;
        pixels.depth[2] = 4.0;
        pixels.normal[5] = Vec3::Y;
        let mut components = vec![[Vec3::ZERO; 6]; 6];
        components[3][4] = Vec3::new(0.25, -1.0, 1e-20);
        pixels.components = Some(components);
        let mut environment = vec![[ExactSum::default(); 3]; 6];
        environment[1][2].add(0.75);
        environment[4][0].add(3e-20);
        pixels.environment = Some(environment);
        PartFile {
            header: PartHeader {
                version: "0.1.0".into(),
                scene: "scènes/a.ron".into(),
                scene_hash: 0xdead_beef,
                settings_hash: 7,
                recorded: RecordedSettings {
                    disabled: crate::features::Features::parse_list("lens,output").unwrap(),
                    integrator: crate::settings::Integrator::Path,
                },
                seed: 42,
                part: Part {
                    index: 2,
                    count: 3,
                    split: Split::Samples,
                },
                width: 3,
                height: 2,
            },
            pixels,
        }
    }

    #[test]
    fn round_trips_every_field() {
        let part = sample();
        let bytes = encode(&part).unwrap();
        assert_eq!(decode(&bytes).unwrap(), part);
        // The same part gives the same bytes (metadata in one attribute, fixed order).
        for _ in 0..4 {
            assert!(encode(&part).unwrap() == bytes);
        }
    }

    /// `bytes` with the metadata text `from` replaced by `to` (the same length, so the EXR
    /// stays readable), as a user editing the header in place would.
    pub(crate) fn edited(bytes: &[u8], from: &str, to: &str) -> Vec<u8> {
        assert_eq!(from.len(), to.len());
        let at = bytes
            .windows(from.len())
            .position(|w| w == from.as_bytes())
            .unwrap_or_else(|| panic!("no {from:?} in the file"));
        let mut out = bytes.to_vec();
        out[at..at + to.len()].copy_from_slice(to.as_bytes());
        out
    }

    #[test]
    fn the_checksum_covers_every_entry_the_merge_relies_on() {
        let bytes = encode(&sample()).unwrap();
        for (from, to) in [
            ("\npart 2/3\n", "\npart 3/3\n"),
            ("\npart 2/3\n", "\npart 2/4\n"),
            ("\nseed 42\n", "\nseed 43\n"),
            ("\nsplit samples\n", "\nsplit tiles\n\n\n"),
            ("\ndisable lens,output\n", "\ndisable output\n\n\n\n\n\n"),
            (
                "\nscene_hash 00000000deadbeef\n",
                "\nscene_hash 00000000deadbeee\n",
            ),
            (
                "\nsettings_hash 0000000000000007\n",
                "\nsettings_hash 0000000000000008\n",
            ),
        ] {
            let e = decode(&edited(&bytes, from, to)).unwrap_err();
            assert_eq!(
                e, "damaged part file (its metadata or data do not match its checksum)",
                "{from:?} → {to:?}"
            );
        }
    }

    #[test]
    fn files_of_an_older_format_are_refused_with_the_rerun_help() {
        let bytes = encode(&sample()).unwrap();
        let old = edited(
            &bytes,
            "format stagelight part 5",
            "format stagelight part 3",
        );
        assert_eq!(
            decode(&old).unwrap_err(),
            "part file of the older format \"stagelight part 3\", whose checksum leaves out its part number and settings (this stagelight writes \"stagelight part 5\")\n  help: render the parts again with this stagelight (`stagelight render --part K/N`)"
        );
        let old = edited(
            &bytes,
            "format stagelight part 5",
            "format stagelight part 4",
        );
        assert_eq!(
            decode(&old).unwrap_err(),
            "part file of the older format \"stagelight part 4\", which leaves out the environment's share of partly covered pixels (this stagelight writes \"stagelight part 5\")\n  help: render the parts again with this stagelight (`stagelight render --part K/N`)"
        );
    }

    #[test]
    fn truncated_and_foreign_files_are_refused() {
        let bytes = encode(&sample()).unwrap();
        let e = decode(&bytes[..bytes.len() / 2]).unwrap_err();
        assert!(e.contains("truncated") || e.starts_with("damaged"), "{e}");
        assert_eq!(decode(b"not an exr").unwrap_err(), NOT_EXR);
        assert_eq!(decode(b"\x89PNG\r\n\x1a\n").unwrap_err(), NOT_EXR);
        let e = decode(&bytes[..3]).unwrap_err();
        assert!(e.starts_with("not a readable EXR file"), "{e}");
    }
}

//! glTF materials → `MetallicRoughness` materials: base colour, metallic and roughness
//! factors, the base colour texture (sRGB) times the vertex colours (`COLOR_0`, bound only
//! when a primitive drawn with the material has them) and the metallic-roughness texture (linear: blue
//! is metalness, green roughness) as shader-graph bindings, the normal texture as a
//! tangent-space normal map (`bump: (normal_map: …, scale)`), emission
//! (`emissiveFactor × KHR_materials_emissive_strength`, W/(sr·m²), times the emissive
//! texture through the `emission` binding), `doubleSided`, and the alpha modes as an
//! `Opacity` wrapper whose opacity is the coverage: `MASK` a step at `alphaCutoff` of the
//! base colour alpha (factor × texture), `BLEND` that alpha itself. The occlusion texture is
//! not read (the light transport computes occlusion; see docs/gltf.md). A texture
//! reference's `KHR_texture_transform` maps the coordinates its image nodes read
//! ([`texture_transform`]). What is not mapped (textures on `TEXCOORD_1`, mirrored or
//! per-axis sampler wrap modes, a normal texture's rotation of its normals) is a located
//! warning.
//!
//! Textures: an image beside the file is bound by its file name; an image inside the file
//! (a buffer view or a `data:` URI) as `<file>#images[i]`, which the image loader reads from
//! the glTF file.

use std::collections::BTreeMap;
use std::path::Path;

use super::json_positions::{value_position, Step};
use super::texture_transform::{self, UvTransform};
use super::Walk;
use crate::scene::desc::{BumpDesc, InputDesc, MaterialDesc, NodeDesc, SceneDesc, ShaderDesc};
use crate::scene::import::SourcePos;
use crate::scene::mesh_files::gltf_file::GltfFile;
use crate::scene::message::Diagnostic;
use crate::scene::nodes_desc::{AxisWrapDesc, EncodingDesc, WrapDesc, EMISSION};

/// Material extensions this reader reads (`KHR_materials_emissive_strength`) or has no use
/// for: `MSFT_lightmap` holds a baked lightmap (what `--write-gltf` writes), light the path
/// tracer computes itself, as for the occlusion texture.
const MATERIAL_EXTENSIONS_READ: [&str; 2] = ["KHR_materials_emissive_strength", "MSFT_lightmap"];

/// How many materials a warning about an unread extension names before "and N more".
const MATERIALS_NAMED: usize = 4;

/// Warns once about file-level features the reader does not map: animations, each material
/// extension it does not read (naming the materials that use it), and each other extension
/// the file requires that it does not support.
pub fn warn_unmapped(w: &mut Walk<'_>) {
    if w.file.doc.animations().count() > 0 {
        let d = located(
            w,
            &[Step::Key("animations")],
            "ignored the file's animations (the scene is read at rest)".into(),
        );
        w.warnings.push(d);
    }
    // Each unread extension: the (index, name) of the materials using it.
    let mut unread: BTreeMap<String, Vec<(usize, Option<&str>)>> = BTreeMap::new();
    for (i, m) in w.file.doc.as_json().materials.iter().enumerate() {
        let others = m.extensions.iter().flat_map(|e| e.others.keys());
        for ext in others {
            if !MATERIAL_EXTENSIONS_READ.contains(&ext.as_str()) {
                let name = super::given(m.name.as_deref());
                unread.entry(ext.clone()).or_default().push((i, name));
            }
        }
    }
    for (ext, users) in &unread {
        let mut named: Vec<String> = users
            .iter()
            .take(MATERIALS_NAMED)
            .map(|(i, name)| match name {
                Some(n) => format!("materials[{i}] (\"{n}\")"),
                None => format!("materials[{i}]"),
            })
            .collect();
        if users.len() > MATERIALS_NAMED {
            named.push(format!("{} more", users.len() - MATERIALS_NAMED));
        }
        let list = match named.split_last() {
            Some((last, [])) => last.clone(),
            Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
            None => String::new(),
        };
        let first = users[0].0;
        let path = [
            Step::Key("materials"),
            Step::Index(first),
            Step::Key("extensions"),
            Step::Key(ext),
        ];
        let d = located(
            w,
            &path,
            format!(
                "ignored \"{ext}\" on {list}: this reader does not support the extension, so the material{} render{} without it",
                if users.len() == 1 { "" } else { "s" },
                if users.len() == 1 { "s" } else { "" },
            ),
        );
        w.warnings.push(d);
    }
    for (k, ext) in w.file.doc.extensions_required().enumerate() {
        if !matches!(
            ext,
            "KHR_lights_punctual" | "KHR_materials_emissive_strength" | "KHR_texture_transform"
        ) && !unread.contains_key(ext)
        {
            let d = located(
                w,
                &[Step::Key("extensionsRequired"), Step::Index(k)],
                format!(
                    "extensionsRequired: ignored \"{ext}\", which this reader does not support"
                ),
            );
            w.warnings.push(d);
        }
    }
}

/// The material name of glTF material `index` (`None`: the glTF default material), added
/// to the scene on first use.
pub fn material_name(w: &mut Walk<'_>, index: Option<usize>) -> String {
    if let Some(name) = w.materials.get(&index) {
        return name.clone();
    }
    let desc = match index.and_then(|i| w.file.doc.materials().nth(i)) {
        Some(m) => material(w, &m),
        None => MaterialDesc {
            name: w.names.materials.take("gltf_default_material"),
            shader: ShaderDesc::MetallicRoughness {
                base_color: (1.0, 1.0, 1.0),
                metallic: 1.0,
                roughness: 1.0,
            },
            two_sided: false,
            emission: (0.0, 0.0, 0.0),
            bind: if uses_vertex_colours(w, None) {
                BTreeMap::from([("base_color".to_string(), node(NodeDesc::VertexColor))])
            } else {
                BTreeMap::new()
            },
            bump: None,
            interior: None,
            contour: None,
            lights: None,
            shadow: None,
            environment: None,
            photon: None,
        },
    };
    let name = desc.name.clone();
    w.desc.materials.push(desc);
    w.materials.insert(index, name.clone());
    name
}

/// Whether a primitive drawn with glTF material `index` (`None`: the default material) has
/// vertex colours (`COLOR_0`).
fn uses_vertex_colours(w: &Walk<'_>, index: Option<usize>) -> bool {
    w.file
        .doc
        .meshes()
        .flat_map(|m| m.primitives())
        .any(|p| p.material().index() == index && p.get(&gltf::Semantic::Colors(0)).is_some())
}

fn node(n: NodeDesc) -> InputDesc {
    InputDesc::Node(Box::new(n))
}

fn material(w: &mut Walk<'_>, m: &gltf::Material<'_>) -> MaterialDesc {
    let index = m.index().unwrap_or(0);
    let name = match super::given(m.name()) {
        Some(given) => w.names.materials.take_given(given),
        None => w.names.materials.take(&format!("material{index}")),
    };
    let pbr = m.pbr_metallic_roughness();
    let [r, g, b, alpha] = pbr.base_color_factor().map(f64::from);
    let metallic = (pbr.metallic_factor() as f64).clamp(0.0, 1.0);
    let roughness = (pbr.roughness_factor() as f64).clamp(0.0, 1.0);
    let unit = |x: f64| x.clamp(0.0, 1.0);
    let mut bind = BTreeMap::new();
    let base_texture = pbr
        .base_color_texture()
        .and_then(|info| texture(w, &info, index, &BASE_COLOUR));
    let factor = InputDesc::Colour((unit(r), unit(g), unit(b)));
    let base = base_texture
        .as_ref()
        .map(|t| node(NodeDesc::Mul(t.image(EncodingDesc::Srgb), factor.clone())));
    // COLOR_0 multiplies the base colour (white where a primitive has none).
    let base = match (base, uses_vertex_colours(w, m.index())) {
        (Some(base), true) => Some(node(NodeDesc::Mul(base, node(NodeDesc::VertexColor)))),
        (None, true) => Some(node(NodeDesc::Mul(factor, node(NodeDesc::VertexColor)))),
        (base, false) => base,
    };
    if let Some(base) = base {
        bind.insert("base_color".to_string(), base);
    }
    if let Some(t) = pbr
        .metallic_roughness_texture()
        .and_then(|info| texture(w, &info, index, &METALLIC_ROUGHNESS))
    {
        let image = t.image(EncodingDesc::Linear);
        let channel = |c: u32, f: f64| {
            node(NodeDesc::Mul(
                node(NodeDesc::Channel(image.clone(), c)),
                InputDesc::Number(f),
            ))
        };
        bind.insert("metallic".to_string(), channel(2, metallic));
        bind.insert("roughness".to_string(), channel(1, roughness));
    }
    let bump = m.normal_texture().and_then(|n| {
        let transform = n.extension_value(TRANSFORM).map(texture_transform::parse);
        let t = texture_ref(w, n.tex_coord(), n.texture(), transform, index, &NORMAL)?;
        Some(BumpDesc {
            height: None,
            normal_map: Some(t.image(EncodingDesc::Linear)),
            object_normal: None,
            scale: n.scale() as f64,
        })
    });
    let strength = m.emissive_strength().unwrap_or(1.0) as f64;
    let [er, eg, eb] = m.emissive_factor().map(|x| (x as f64 * strength).max(0.0));
    let emits = er > 0.0 || eg > 0.0 || eb > 0.0;
    let mut emission_map = m
        .emissive_texture()
        .filter(|_| emits)
        .and_then(|info| texture(w, &info, index, &EMISSIVE))
        .map(|t| t.image(EncodingDesc::Srgb));
    let mut shader = ShaderDesc::MetallicRoughness {
        base_color: (unit(r), unit(g), unit(b)),
        metallic,
        roughness,
    };
    // Coverage: the share of the surface that is there (glTF's alpha after the mode).
    let texture_alpha = |x: f64| {
        base_texture
            .as_ref()
            .map(|t| node(NodeDesc::Mul(t.alpha(), InputDesc::Number(x))))
    };
    let coverage = match m.alpha_mode() {
        gltf::material::AlphaMode::Opaque => None,
        gltf::material::AlphaMode::Mask => {
            let cutoff = m.alpha_cutoff().unwrap_or(0.5) as f64;
            match texture_alpha(alpha) {
                Some(a) => Some(Coverage::Varying(node(NodeDesc::Smoothstep {
                    edge0: InputDesc::Number(cutoff),
                    edge1: InputDesc::Number(cutoff),
                    x: a,
                }))),
                None if alpha >= cutoff => None,
                None => Some(Coverage::Constant(0.0)),
            }
        }
        gltf::material::AlphaMode::Blend => match texture_alpha(unit(alpha)) {
            Some(a) => Some(Coverage::Varying(a)),
            None if alpha < 1.0 => Some(Coverage::Constant(unit(alpha))),
            None => None,
        },
    };
    if let Some(coverage) = coverage {
        shader = ShaderDesc::Opacity {
            opacity: (1.0, 1.0, 1.0),
            input: Box::new(shader),
        };
        bind = bind
            .into_iter()
            .map(|(k, v)| (format!("input.{k}"), v))
            .collect();
        let c = match coverage {
            Coverage::Varying(c) => c,
            Coverage::Constant(c) => InputDesc::Number(c),
        };
        if let (InputDesc::Number(x), ShaderDesc::Opacity { opacity, .. }) = (&c, &mut shader) {
            *opacity = (*x, *x, *x);
        } else {
            bind.insert("opacity".to_string(), c.clone());
        }
        // Where the surface is not there, it does not emit either.
        if emits {
            let map = emission_map.take().unwrap_or(InputDesc::Number(1.0));
            emission_map = Some(node(NodeDesc::Mul(map, c)));
        }
    }
    if let Some(map) = emission_map {
        bind.insert(EMISSION.to_string(), map);
    }
    MaterialDesc {
        name,
        shader,
        two_sided: m.double_sided(),
        emission: (er, eg, eb),
        bind,
        bump,
        interior: None,
        contour: None,
        lights: None,
        shadow: None,
        environment: None,
        photon: None,
    }
}

/// How much of a surface is there: glTF's alpha after the alpha mode.
enum Coverage {
    /// The same everywhere.
    Constant(f64),
    /// A scalar node (the texture's alpha, cut at the cutoff for `MASK`).
    Varying(InputDesc),
}

/// An image of the file bound to a material: its file reference, wrap mode and texture
/// coordinates (`Uv`, or `KHR_texture_transform`'s map of them).
struct TextureRef {
    file: String,
    wrap: WrapDesc,
    uv: InputDesc,
}

impl TextureRef {
    /// The image's colour, decoded as `encoding` says.
    fn image(&self, encoding: EncodingDesc) -> InputDesc {
        node(NodeDesc::Image {
            file: self.file.clone(),
            uv: self.uv.clone(),
            wrap: self.wrap,
            color_space: Some(encoding),
        })
    }

    /// The image's alpha (1 for images without one).
    fn alpha(&self) -> InputDesc {
        node(NodeDesc::Alpha {
            file: self.file.clone(),
            uv: self.uv.clone(),
            wrap: self.wrap,
        })
    }
}

/// Reports an image file beside the glTF file that cannot be read (missing, a directory,
/// unreadable): at its `uri` in a `.gltf`, naming the image (index and name) and the
/// material texture `user` that binds it; once per image.
fn check_image_file(w: &mut Walk<'_>, image: &gltf::Image<'_>, name: &str, user: &str) {
    let path = w.path.parent().unwrap_or(Path::new("")).join(name);
    let reason = match std::fs::metadata(&path) {
        Ok(m) if m.is_file() => return,
        Ok(_) => "it is not a file".to_string(),
        Err(e) => crate::scene::message::io_reason(&e),
    };
    let index = image.index();
    let (line, column) = w
        .json
        .and_then(|json| value_position(json, &image_uri(index)))
        .unwrap_or((1, 1));
    if w.errors.iter().any(|e| {
        e.line == line && e.column == column && e.message.contains(&format!("images[{index}]"))
    }) {
        return;
    }
    let label = match image.name() {
        Some(n) => format!("images[{index}] (\"{n}\")"),
        None => format!("images[{index}]"),
    };
    w.errors.push(Diagnostic {
        file: w.path.to_path_buf(),
        line,
        column,
        message: format!(
            "{user} {label}: cannot read image file \"{}\": {reason}",
            path.display()
        ),
        help: Some(
            "expected a PNG file at the image's uri, relative to the glTF file: put the file there, correct the uri, or embed the image (a bufferView or a base64 data: URI)".into(),
        ),
    });
}

/// The path of image `index`'s `uri` in the JSON.
fn image_uri(index: usize) -> [Step<'static>; 3] {
    [Step::Key("images"), Step::Index(index), Step::Key("uri")]
}

/// Positions for the shared loader's messages about a `.gltf` file's images (an image file
/// that is there but does not decode): each material binding and normal map that reads an
/// image beside the file is located at that image's `uri`.
pub fn image_positions(
    desc: &SceneDesc,
    file: &GltfFile,
    path: &Path,
    json: &[u8],
) -> Vec<(String, SourcePos)> {
    let uris: Vec<Option<String>> = file
        .doc
        .images()
        .map(|image| match image.source() {
            gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => {
                Some(crate::scene::mesh_files::gltf_file::percent_decode(uri))
            }
            _ => None,
        })
        .collect();
    let mut out = Vec::new();
    for (k, m) in desc.materials.iter().enumerate() {
        let inputs = m
            .bind
            .iter()
            .map(|(key, input)| (format!("materials[{k}].bind.{key}"), input))
            .chain(
                m.bump
                    .iter()
                    .filter_map(|b| b.normal_map.as_ref())
                    .map(|input| (format!("materials[{k}].bump.normal_map"), input)),
            );
        for (at, input) in inputs {
            let Some(name) = image_file(input) else {
                continue;
            };
            let Some(index) = uris.iter().position(|u| u.as_deref() == Some(name)) else {
                continue;
            };
            if let Some((line, column)) = value_position(json, &image_uri(index)) {
                let file = path.to_path_buf();
                out.push((at, SourcePos { file, line, column }));
            }
        }
    }
    out
}

/// The file of the first image node in a binding the reader wrote.
fn image_file(input: &InputDesc) -> Option<&str> {
    let InputDesc::Node(node) = input else {
        return None;
    };
    match &**node {
        NodeDesc::Image { file, .. } | NodeDesc::Alpha { file, .. } => Some(file),
        NodeDesc::Mul(a, b) => image_file(a).or_else(|| image_file(b)),
        NodeDesc::Channel(a, _) => image_file(a),
        NodeDesc::Smoothstep { x, .. } => image_file(x),
        _ => None,
    }
}

/// The glTF extension that maps a texture reference's coordinates.
const TRANSFORM: &str = "KHR_texture_transform";

/// A material's texture slot: its name in messages and its keys in the material's JSON.
struct Slot {
    what: &'static str,
    keys: &'static [&'static str],
}

const BASE_COLOUR: Slot = Slot {
    what: "base colour",
    keys: &["pbrMetallicRoughness", "baseColorTexture"],
};
const METALLIC_ROUGHNESS: Slot = Slot {
    what: "metallic-roughness",
    keys: &["pbrMetallicRoughness", "metallicRoughnessTexture"],
};
const NORMAL: Slot = Slot {
    what: "normal",
    keys: &["normalTexture"],
};
const EMISSIVE: Slot = Slot {
    what: "emissive",
    keys: &["emissiveTexture"],
};

impl Slot {
    /// The JSON path of `materials[material].<slot>.extensions.KHR_texture_transform.<key>`.
    fn transform_path<'a>(&self, material: usize, key: &'a str) -> Vec<Step<'a>> {
        let mut path = vec![Step::Key("materials"), Step::Index(material)];
        path.extend(self.keys.iter().map(|k| Step::Key(k)));
        path.extend([
            Step::Key("extensions"),
            Step::Key(TRANSFORM),
            Step::Key(key),
        ]);
        path
    }
}

/// A diagnostic at `path` (or its nearest enclosing element) in a `.gltf`, at the start
/// of a `.glb`.
fn located(w: &Walk<'_>, path: &[Step<'_>], message: String) -> Diagnostic {
    super::at_element(w, path, message)
}

/// The image of a texture reference, or `None` (with a warning) when it cannot be bound.
fn texture(
    w: &mut Walk<'_>,
    info: &gltf::texture::Info<'_>,
    material: usize,
    slot: &Slot,
) -> Option<TextureRef> {
    let transform = info.texture_transform().map(|t| {
        Ok(UvTransform {
            offset: t.offset().map(f64::from),
            rotation: f64::from(t.rotation()),
            scale: t.scale().map(f64::from),
            tex_coord: t.tex_coord(),
        })
    });
    texture_ref(
        w,
        info.tex_coord(),
        info.texture(),
        transform,
        material,
        slot,
    )
}

/// The image of a texture reference with its `KHR_texture_transform` (`transform`: the
/// `gltf` crate reads it for texture infos, [`texture_transform::parse`] for the normal
/// texture, which the crate does not model), or
/// `None` where it cannot be bound (a warning) or the extension is malformed (an error).
fn texture_ref(
    w: &mut Walk<'_>,
    tex_coord: u32,
    texture: gltf::Texture<'_>,
    transform: Option<Result<UvTransform, texture_transform::Malformed>>,
    material: usize,
    slot: &Slot,
) -> Option<TextureRef> {
    let at = format!("materials[{material}]");
    let what = slot.what;
    let transform = match transform {
        None => None,
        Some(Ok(t)) => Some(t),
        Some(Err((key, expected))) => {
            let path = slot.transform_path(material, key);
            let mut d = located(
                w,
                &path,
                format!("{at}: the {what} texture's {TRANSFORM} \"{key}\" must be {expected}"),
            );
            d.help = Some(
                "the extension's members: \"offset\": [u, v], \"rotation\": radians, \"scale\": [u, v], \"texCoord\": a set index".into(),
            );
            w.errors.push(d);
            return None;
        }
    };
    let tex_coord = transform.and_then(|t| t.tex_coord).unwrap_or(tex_coord);
    if tex_coord != 0 {
        let mut path = vec![Step::Key("materials"), Step::Index(material)];
        path.extend(slot.keys.iter().map(|k| Step::Key(k)));
        path.push(Step::Key("texCoord"));
        let d = located(
            w,
            &path,
            format!(
                "{at}: ignored its {what} texture on TEXCOORD_{tex_coord} (shading reads TEXCOORD_0 only)"
            ),
        );
        w.warnings.push(d);
        return None;
    }
    if let Some(t) = transform.filter(|t| what == NORMAL.what && t.rotation != 0.0) {
        let path = slot.transform_path(material, "rotation");
        let d = located(
            w,
            &path,
            format!(
                "{at}: the normal texture's {TRANSFORM} rotation ({} rad) turns where the map is read, not its normals: they stay in the mesh's tangent frame",
                t.rotation
            ),
        );
        w.warnings.push(d);
    }
    let image = texture.source();
    let file = match image.source() {
        gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => {
            let name = crate::scene::mesh_files::gltf_file::percent_decode(uri);
            check_image_file(w, &image, &name, &format!("{at}: {what} texture"));
            name
        }
        _ => format!("{}#images[{}]", super::file_name_of(w.path), image.index()),
    };
    let wrap = wrap(&texture);
    let uv = transform.map_or(node(NodeDesc::Uv), |t| t.uv_node());
    Some(TextureRef { file, wrap, uv })
}

/// The wrap of a texture's sampler, axis by axis: `wrapS` is u (across the image), `wrapT`
/// is v; `CLAMP_TO_EDGE` → `Clamp`, `MIRRORED_REPEAT` → `Mirror`, `REPEAT` → `Repeat`
/// (one mode when both axes agree, else `PerAxis`). glTF's t runs down the image where v
/// runs up it, which no wrap mode tells apart.
fn wrap(texture: &gltf::Texture<'_>) -> WrapDesc {
    use gltf::texture::WrappingMode;
    let axis = |m: WrappingMode| match m {
        WrappingMode::ClampToEdge => AxisWrapDesc::Clamp,
        WrappingMode::MirroredRepeat => AxisWrapDesc::Mirror,
        WrappingMode::Repeat => AxisWrapDesc::Repeat,
    };
    let sampler = texture.sampler();
    WrapDesc::from_axes(axis(sampler.wrap_s()), axis(sampler.wrap_t()))
}

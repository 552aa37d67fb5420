//! glTF materials → `MetallicRoughness` materials: base colour, metallic and roughness
//! factors, the base colour texture (sRGB) and the metallic-roughness texture (linear: blue
//! is metalness, green roughness) as shader-graph bindings, emission
//! (`emissiveFactor × KHR_materials_emissive_strength`, W/(sr·m²)), `doubleSided`, and
//! `BLEND` with a constant alpha as an `Opacity` wrapper. What is not mapped (normal,
//! occlusion and emissive textures, `MASK`, textures on `TEXCOORD_1`, texture transforms) is
//! a located warning.
//!
//! Textures: an image beside the file is bound by its file name; an image inside the file
//! (a buffer view or a `data:` URI) as `<file>#images[i]`, which the image loader reads from
//! the glTF file.

use std::collections::BTreeMap;

use super::{at_file, Walk};
use crate::scene::desc::{InputDesc, MaterialDesc, NodeDesc, ShaderDesc};
use crate::scene::nodes_desc::{EncodingDesc, WrapDesc};

/// Warns once about file-level features the reader does not map.
pub fn warn_unmapped(w: &mut Walk<'_>) {
    if w.file.doc.animations().count() > 0 {
        w.warnings.push(at_file(
            w.path,
            "ignored the file's animations (the scene is read at rest)",
        ));
    }
    for ext in w.file.doc.extensions_required() {
        if !matches!(
            ext,
            "KHR_lights_punctual" | "KHR_materials_emissive_strength"
        ) {
            w.warnings.push(at_file(
                w.path,
                format!(
                    "extensionsRequired: ignored \"{ext}\", which this reader does not support"
                ),
            ));
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
            name: w.names.take("gltf_default_material"),
            shader: ShaderDesc::MetallicRoughness {
                base_color: (1.0, 1.0, 1.0),
                metallic: 1.0,
                roughness: 1.0,
            },
            two_sided: false,
            emission: (0.0, 0.0, 0.0),
            bind: BTreeMap::new(),
            bump: None,
            interior: None,
            contour: None,
            lights: None,
        },
    };
    let name = desc.name.clone();
    w.desc.materials.push(desc);
    w.materials.insert(index, name.clone());
    name
}

fn node(n: NodeDesc) -> InputDesc {
    InputDesc::Node(Box::new(n))
}

fn material(w: &mut Walk<'_>, m: &gltf::Material<'_>) -> MaterialDesc {
    let index = m.index().unwrap_or(0);
    let label = m
        .name()
        .map(str::to_string)
        .unwrap_or_else(|| format!("material{index}"));
    let name = w.names.take(&label);
    let at = format!("materials[{index}]");
    let pbr = m.pbr_metallic_roughness();
    let [r, g, b, alpha] = pbr.base_color_factor().map(f64::from);
    let metallic = (pbr.metallic_factor() as f64).clamp(0.0, 1.0);
    let roughness = (pbr.roughness_factor() as f64).clamp(0.0, 1.0);
    let unit = |x: f64| x.clamp(0.0, 1.0);
    let mut bind = BTreeMap::new();
    if let Some(info) = pbr.base_color_texture() {
        if let Some(image) = texture(w, &info, EncodingDesc::Srgb, &at, "base colour") {
            let factor = InputDesc::Colour((unit(r), unit(g), unit(b)));
            bind.insert("base_color".to_string(), node(NodeDesc::Mul(image, factor)));
        }
    }
    if let Some(info) = pbr.metallic_roughness_texture() {
        if let Some(image) = texture(w, &info, EncodingDesc::Linear, &at, "metallic-roughness") {
            let channel = |c: u32, f: f64| {
                node(NodeDesc::Mul(
                    node(NodeDesc::Channel(image.clone(), c)),
                    InputDesc::Number(f),
                ))
            };
            bind.insert("metallic".to_string(), channel(2, metallic));
            bind.insert("roughness".to_string(), channel(1, roughness));
        }
    }
    let ignored = [
        ("normal texture", m.normal_texture().is_some()),
        ("occlusion texture", m.occlusion_texture().is_some()),
        ("emissive texture", m.emissive_texture().is_some()),
    ];
    for (what, present) in ignored {
        if present {
            w.warnings.push(at_file(
                w.path,
                format!("{at}: ignored its {what} (not supported yet; see docs/gltf.md)"),
            ));
        }
    }
    let strength = m.emissive_strength().unwrap_or(1.0) as f64;
    let [er, eg, eb] = m.emissive_factor().map(|x| (x as f64 * strength).max(0.0));
    let mut shader = ShaderDesc::MetallicRoughness {
        base_color: (unit(r), unit(g), unit(b)),
        metallic,
        roughness,
    };
    match m.alpha_mode() {
        gltf::material::AlphaMode::Opaque => {}
        gltf::material::AlphaMode::Mask => w.warnings.push(at_file(
            w.path,
            format!(
                "{at}: alphaMode MASK is read as OPAQUE (alpha cut-outs are not supported yet)"
            ),
        )),
        gltf::material::AlphaMode::Blend => {
            if pbr.base_color_texture().is_some() {
                w.warnings.push(at_file(
                    w.path,
                    format!("{at}: alphaMode BLEND uses the base colour factor's alpha only (the texture's alpha is ignored)"),
                ));
            }
            if alpha < 1.0 {
                let a = unit(alpha);
                shader = ShaderDesc::Opacity {
                    opacity: (a, a, a),
                    input: Box::new(shader),
                };
                bind = bind
                    .into_iter()
                    .map(|(k, v)| (format!("input.{k}"), v))
                    .collect();
            }
        }
    }
    MaterialDesc {
        name,
        shader,
        two_sided: m.double_sided(),
        emission: (er, eg, eb),
        bind,
        bump: None,
        interior: None,
        contour: None,
        lights: None,
    }
}

/// The image node of a texture reference, or `None` (with a warning) when it cannot be
/// bound.
fn texture(
    w: &mut Walk<'_>,
    info: &gltf::texture::Info<'_>,
    encoding: EncodingDesc,
    at: &str,
    what: &str,
) -> Option<InputDesc> {
    if info.tex_coord() != 0 {
        w.warnings.push(at_file(
            w.path,
            format!(
                "{at}: ignored its {what} texture on TEXCOORD_{} (shading reads TEXCOORD_0 only)",
                info.tex_coord()
            ),
        ));
        return None;
    }
    let texture = info.texture();
    let image = texture.source();
    let file = match image.source() {
        gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => {
            crate::scene::mesh_files::gltf_file::percent_decode(uri)
        }
        _ => format!("{}#images[{}]", super::file_name_of(w.path), image.index()),
    };
    use gltf::texture::WrappingMode;
    let sampler = texture.sampler();
    let wrap = match (sampler.wrap_s(), sampler.wrap_t()) {
        (WrappingMode::ClampToEdge, WrappingMode::ClampToEdge) => WrapDesc::Clamp,
        _ => WrapDesc::Repeat,
    };
    Some(node(NodeDesc::Image {
        file,
        uv: node(NodeDesc::Uv),
        wrap,
        color_space: Some(encoding),
    }))
}

//! Where each built-in shader parameter lands in the description, so that a value written
//! as a shader parameter is located at its value ([`super::value_positions`]): per shader,
//! its parameters and the description paths below the element they become (a parameter that
//! feeds several fields, or several variants, lists each).

use super::cursor::Cursor;
use super::cursor::ShaderCall;
use super::value_positions::ValuePositions;

type Table = &'static [(&'static str, &'static [&'static str])];

const LOCAL: Table = &[
    ("diffuse", &[".shader.Local.color"]),
    ("specular", &[".shader.Local.specular"]),
    ("ambient", &[".shader.Local.ambient"]),
    ("ambience", &[".shader.Local.ambient"]),
    ("exponent", &[".shader.Local.lobe.Phong.exponent"]),
    (
        "roughness",
        &[
            ".shader.Local.lobe.Blinn.roughness",
            ".shader.Local.lobe.CookTorrance.roughness",
        ],
    ),
    (
        "ior",
        &[
            ".shader.Local.lobe.Blinn.ior",
            ".shader.Local.lobe.CookTorrance.ior",
        ],
    ),
];

const DGS: Table = &[
    ("diffuse", &[".shader.Dgs.diffuse"]),
    ("glossy", &[".shader.Dgs.glossy"]),
    ("specular", &[".shader.Dgs.specular"]),
    ("shiny", &[".shader.Dgs.shiny"]),
];

const DIELECTRIC: Table = &[
    ("ior", &[".shader.Dielectric.ior"]),
    ("ior_out", &[".shader.Dielectric.ior_out"]),
    ("col", &[".shader.Dielectric.col"]),
];

const OPACITY: Table = &[
    ("opacity", &[".shader.Opacity.opacity"]),
    ("input", &[".shader.Opacity.input"]),
];

const LIGHT: Table = &[
    ("color", &[".color"]),
    ("factor", &[".shadow_factor"]),
    ("start", &[".attenuation[0]"]),
    ("stop", &[".attenuation[1]"]),
    ("cone", &[".kind.Spot.penumbra"]),
];

const CONTOUR: Table = &[
    (
        "color",
        &[
            ".contour.Simple.color",
            ".contour.Curvature.color",
            ".contour.Silhouette.color",
            ".contour.Layered.color",
            ".contour.WidthFromLight.color",
        ],
    ),
    (
        "width",
        &[
            ".contour.Simple.width",
            ".contour.FactorColor.width",
            ".contour.Silhouette.width",
            ".contour.Layered.width",
        ],
    ),
    (
        "factor",
        &[".contour.FactorColor.factor", ".contour.Layered.thinning"],
    ),
    ("near_z", &[".contour.DepthFade.near"]),
    ("far_z", &[".contour.DepthFade.far"]),
    ("near_color", &[".contour.DepthFade.near_color"]),
    ("far_color", &[".contour.DepthFade.far_color"]),
    ("near_width", &[".contour.DepthFade.near_width"]),
    ("far_width", &[".contour.DepthFade.far_width"]),
    (
        "min_width",
        &[
            ".contour.Curvature.min_width",
            ".contour.WidthFromLight.lit_width",
        ],
    ),
    (
        "max_width",
        &[
            ".contour.Curvature.max_width",
            ".contour.WidthFromLight.dark_width",
        ],
    ),
];

const CONTRAST: Table = &[
    ("ndelta", &[".contours.contrast.normal_angle"]),
    ("diff_mat", &[".contours.contrast.material"]),
    ("diff_label", &[".contours.contrast.object"]),
    ("diff_index", &[".contours.contrast.instance"]),
    ("max_level", &[".contours.ray_depth"]),
];

/// The table of the shader `name` (none for a shader whose values are not located).
fn table(name: &str) -> Table {
    match name {
        "mib_illum_lambert" | "mib_illum_phong" | "mib_illum_blinn" | "mib_illum_cooktorr" => LOCAL,
        "dgs_material" => DGS,
        "dielectric_material" => DIELECTRIC,
        "mib_opacity" => OPACITY,
        "mib_light_point" | "mib_light_spot" | "mib_light_infinite" | "physical_light" => LIGHT,
        n if n.starts_with("contour_contrast_function") => CONTRAST,
        n if n.starts_with("contour_shader_") => CONTOUR,
        _ => &[],
    }
}

/// Records where `call` (a material, light, contour or contour contrast shader) was
/// written: `whole` (the shader's own path, `.shader`, `.contour`; none for a light) at
/// its name, each parameter at its value.
pub fn record(c: &Cursor, call: &ShaderCall, whole: Option<&str>, values: &mut ValuePositions) {
    if let Some(whole) = whole {
        values.record(whole, c.located(call.pos));
    }
    let table = table(&call.name);
    for p in &call.params {
        let Some((_, paths)) = table.iter().find(|(name, _)| *name == p.name) else {
            continue;
        };
        for path in *paths {
            let at = super::super::located::Located {
                file: call.file.clone(),
                pos: p.value_pos,
            };
            values.record(*path, at);
        }
    }
}

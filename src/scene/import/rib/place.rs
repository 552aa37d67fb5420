//! A primitive onto the description: its material (the surface shader, `Cs`, `Os`,
//! `Sides`, the area light and the lights switched off, shared by every primitive with the
//! same ones), its displacement, shading rate and orientation, one object and the instance that places
//! it — or, inside `ObjectBegin`, the primitive kept for [`super::retained`] to place at
//! each `ObjectInstance` with the attributes current there.

use std::path::{Path, PathBuf};

use super::super::located::{Pos, Problem};
use super::build::{Builder, PendingInstance, PendingMaterial, PendingObject};
use super::geometry::{self, Primitive};
use super::names::Requested;
use super::params::Param;
use super::parse::Request;
use super::retained::RetainedPrim;
use super::shaders;
use super::state::ShaderCall;
use crate::scene::desc::{
    ApproximationDesc, DisplacementDesc, DisplacementModeDesc, MaterialDesc, ShaderDesc, SpaceDesc,
    V3,
};
use crate::scene::nodes_desc::{EncodingDesc, InputDesc, NodeDesc, WrapDesc};

/// What the current attributes make of a primitive besides its mesh.
pub(super) struct Look {
    /// Index into the materials.
    pub material: usize,
    /// The displacement and the paths of its values.
    pub displacement: Option<(DisplacementDesc, Vec<(String, Pos)>)>,
    /// The shading rate as an approximation, and where it was written.
    pub approximation: Option<(ApproximationDesc, Pos)>,
    /// Whether the primitive is inside out (`Orientation`, `ReverseOrientation`).
    pub reverse_orientation: bool,
}

impl Look {
    /// What an object made with this look shares with every instance placing it.
    fn object_key(&self) -> String {
        format!(
            "{:?}|{:?}|{}",
            self.displacement.as_ref().map(|d| &d.0),
            self.approximation.as_ref().map(|a| &a.0),
            self.reverse_orientation
        )
    }
}

impl Builder {
    /// A primitive request: placed now, or kept by the object definition being read.
    pub(super) fn primitive(&mut self, r: &Request, problems: &mut Vec<Problem>) {
        let Some(prim) = geometry::primitive(r, &self.gs.attrs, &self.decls, problems) else {
            return;
        };
        if let Some(d) = &mut self.retained.defining {
            d.prims.push(RetainedPrim {
                prim,
                object_from_prim: self.gs.attrs.ctm,
                base: r.name.to_lowercase(),
                at: (self.file, r.pos),
                variants: Default::default(),
            });
            return;
        }
        let look = self.look(&prim, r.pos, problems);
        let attrs = &self.gs.attrs;
        let requested = Requested {
            base: attrs.name.clone().unwrap_or_else(|| r.name.to_lowercase()),
            given: attrs.name.is_some(),
        };
        let world_from_object = attrs.ctm;
        let object = self.objects.len();
        self.objects.push(PendingObject {
            requested,
            prim,
            material: look.material,
            approximation: look.approximation,
            displacement: look.displacement,
            reverse_orientation: look.reverse_orientation,
            at: (self.file, r.pos),
        });
        self.instances.push(PendingInstance {
            object,
            world_from_object,
            material: None,
            requested: None,
            caustic: attrs.caustic.flag(),
            atmosphere: attrs.atmosphere,
            at: (self.file, r.pos),
        });
    }

    /// `ObjectInstance`: every primitive of the definition `prims`, placed by the current
    /// transformation with the current attributes (at `r`).
    pub(super) fn instance(
        &mut self,
        prims: &mut [RetainedPrim],
        r: &Request,
        problems: &mut Vec<Problem>,
    ) {
        for rp in prims {
            let look = self.look(&rp.prim, r.pos, problems);
            let key = look.object_key();
            let material = look.material;
            let object = match rp.variants.get(&key) {
                Some(&o) => o,
                None => {
                    let o = self.objects.len();
                    self.objects.push(PendingObject {
                        requested: Requested {
                            base: rp.base.clone(),
                            given: false,
                        },
                        prim: rp.prim.clone(),
                        material,
                        approximation: look.approximation,
                        displacement: look.displacement,
                        reverse_orientation: look.reverse_orientation,
                        at: rp.at,
                    });
                    rp.variants.insert(key, o);
                    o
                }
            };
            let attrs = &self.gs.attrs;
            self.instances.push(PendingInstance {
                object,
                world_from_object: attrs.ctm * rp.object_from_prim,
                material: (self.objects[object].material != material).then_some(material),
                requested: Some(Requested {
                    base: attrs.name.clone().unwrap_or_default(),
                    given: attrs.name.is_some(),
                }),
                caustic: attrs.caustic.flag(),
                atmosphere: attrs.atmosphere,
                at: (self.file, r.pos),
            });
        }
    }

    /// The material, displacement and shading rate the current attributes give `prim`
    /// (requested at `at`); marks the lights it is lit by and not.
    fn look(&mut self, prim: &Primitive, at: Pos, problems: &mut Vec<Problem>) -> Look {
        let surface_reported = match self.gs.attrs.surface.clone() {
            Some(s) => self.reported_surface(&s),
            None => false,
        };
        let attrs = &self.gs.attrs;
        let cs = prim.color.unwrap_or(attrs.color);
        let os = prim.opacity.unwrap_or(attrs.opacity);
        let mut sp = Vec::new();
        let surface = shaders::surface(attrs.surface.as_ref(), cs, os, &mut sp);
        let mut bind = match &surface.texture {
            Some((t, tpos)) => self.texture_bind(t, *tpos, cs, &mut sp),
            None => surface.bind.clone(),
        };
        // Parameter problems are reported once, at the Surface request.
        if !surface_reported {
            problems.extend(sp);
        }
        let mut shader = surface.shader;
        let mut spaths: Vec<(String, Pos)> = surface
            .paths
            .into_iter()
            .map(|(p, pos)| (format!(".shader{p}"), pos))
            .collect();
        if os != (1.0, 1.0, 1.0) {
            shader = ShaderDesc::Opacity {
                opacity: os,
                input: Box::new(shader),
            };
            spaths = spaths
                .into_iter()
                .map(|(p, pos)| (p.replacen(".shader", ".shader.Opacity.input", 1), pos))
                .collect();
            bind = bind
                .into_iter()
                .map(|(k, v)| (format!("input.{k}"), v))
                .collect();
        }
        let bind_pos = match (&surface.texture, &attrs.surface) {
            (Some((_, tpos)), _) => Some(*tpos),
            (None, Some(s)) if !surface.bind.is_empty() => Some(s.pos),
            _ => None,
        };
        if let Some(pos) = bind_pos {
            for k in bind.keys() {
                spaths.push((format!(".bind.{k}"), pos));
            }
        }
        spaths.extend(
            surface
                .bump_paths
                .iter()
                .map(|(p, pos)| (format!(".bump{p}"), *pos)),
        );
        let emission = attrs.area_light.as_ref().map(|c| {
            let find = |n: &str| c.params.iter().find(|p| p.name == n);
            let i = find("intensity").map_or(1.0, Param::num);
            let col = find("lightcolor").map_or((1.0, 1.0, 1.0), Param::triple);
            (col.0 * i, col.1 * i, col.2 * i)
        });
        let (photon, ppaths) = self.photon_shader();
        spaths.extend(ppaths);
        let attrs = &self.gs.attrs;
        let at_pos = attrs.surface.as_ref().map_or(at, |s| s.pos);
        let at_file = attrs.surface.as_ref().map_or(self.file, |s| s.file);
        let desc = MaterialDesc {
            name: String::new(),
            shader,
            two_sided: attrs.sides == 2,
            emission: emission.unwrap_or((0.0, 0.0, 0.0)),
            bind,
            bump: surface.bump,
            interior: None,
            contour: None,
            lights: None,
            shadow: None,
            environment: None,
            photon,
        };
        let mut lights_off = attrs.lights_off.clone();
        lights_off.sort_unstable();
        lights_off.dedup();
        let area_light = attrs.area_light_id.filter(|_| emission.is_some());
        let key = format!(
            "{:?}|{:?}|{:?}|{}|{:?}|{}|{:?}|{:?}|{:?}",
            desc.shader,
            desc.bind,
            desc.bump,
            desc.two_sided,
            desc.emission,
            at_pos.line * 100_000 + at_pos.column,
            lights_off,
            desc.photon,
            area_light
        );
        let material = match self.material_keys.get(&key) {
            Some(&m) => m,
            None => {
                let m = self.materials.len();
                let base = attrs
                    .surface
                    .as_ref()
                    .map_or("defaultsurface", |s| s.name.as_str());
                let mut desc = desc;
                desc.name = format!("{base}_{}", m + 1);
                self.materials.push(PendingMaterial {
                    desc,
                    paths: spaths,
                    at: (at_file, at_pos),
                    lights_off,
                    area_light,
                });
                self.material_keys.insert(key, m);
                m
            }
        };
        let displacement = attrs.displacement.as_ref().and_then(|d| {
            // Its problems were reported at the Displacement request.
            let shader = shaders::displacement(d, &mut Vec::new())?;
            let mut paths = vec![(String::new(), d.pos), (".shader".to_string(), d.pos)];
            let bound = attrs.displacement_bound.map(|(b, pos)| {
                paths.push((".bound".into(), pos));
                b
            });
            Some((
                DisplacementDesc {
                    shader,
                    bound,
                    mode: if attrs.true_displacement {
                        DisplacementModeDesc::True
                    } else {
                        DisplacementModeDesc::Bump
                    },
                },
                paths,
            ))
        });
        let approximation = attrs.shading_rate.map(|(rate, pos)| {
            (
                ApproximationDesc::Spatial {
                    edge: rate.sqrt(),
                    space: SpaceDesc::Raster,
                    min_subdiv: 0,
                    max_subdiv: 7,
                },
                pos,
            )
        });
        self.area_lights
            .place(attrs.area_light_id, &attrs.area_lights_off);
        for (i, l) in self.lights.iter_mut().enumerate() {
            if attrs.lights_off.contains(&i) {
                l.used_off = true;
            } else {
                l.used_on = true;
            }
        }
        Look {
            material,
            displacement,
            approximation,
            reverse_orientation: attrs.inside_out,
        }
    }

    /// `paintedplastic`'s `texturename` as a binding of the `Local` colour: `Cs` times the
    /// image, looked up at RenderMan's `(s, t)` (`t` runs down the image, so the image's
    /// `v` is `1 − t`), values taken as stored (linear). RenderMan texture files (`.tex`,
    /// `.tx`, TIFF) are not read: the PNG or EXR of the same name beside them is, with a
    /// warning; without one the texture is white.
    fn texture_bind(
        &self,
        name: &str,
        pos: Pos,
        cs: V3,
        problems: &mut Vec<Problem>,
    ) -> std::collections::BTreeMap<String, InputDesc> {
        let mut bind = std::collections::BTreeMap::new();
        let dir = self.files[self.file]
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default();
        let root = self.files[0]
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default();
        let written = Path::new(name);
        let readable = |p: &Path| {
            p.extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| matches!(e.to_ascii_lowercase().as_str(), "png" | "exr"))
        };
        let candidates: Vec<PathBuf> = if readable(written) {
            vec![written.to_path_buf()]
        } else {
            ["png", "exr"]
                .iter()
                .map(|e| written.with_extension(e))
                .collect()
        };
        let Some(found) = candidates.into_iter().find(|c| dir.join(c).is_file()) else {
            problems.push(Problem::warning(
                pos,
                format!(
                    "ignored \"texturename\" \"{name}\": no PNG or EXR file of that name \
                     (RenderMan texture files are not read): the surface is untextured"
                ),
            ));
            return bind;
        };
        if found.as_path() != written {
            problems.push(Problem::warning(
                pos,
                format!(
                    "reading \"{}\" for texture \"{name}\": stagelight reads PNG and EXR",
                    found.display()
                ),
            ));
        }
        let full = dir.join(&found);
        let file = full
            .strip_prefix(&root)
            .map(Path::to_path_buf)
            .unwrap_or(full)
            .display()
            .to_string();
        let node = |n: NodeDesc| InputDesc::Node(Box::new(n));
        let uv = || node(NodeDesc::Uv);
        let st = node(NodeDesc::Combine(
            node(NodeDesc::Channel(uv(), 0)),
            node(NodeDesc::Sub(
                InputDesc::Number(1.0),
                node(NodeDesc::Channel(uv(), 1)),
            )),
            InputDesc::Number(0.0),
        ));
        let image = node(NodeDesc::Image {
            file,
            uv: st,
            wrap: WrapDesc::Repeat,
            color_space: Some(EncodingDesc::Linear),
        });
        bind.insert(
            "color".to_string(),
            node(NodeDesc::Mul(InputDesc::Colour(cs), image)),
        );
        bind
    }

    /// Whether the problems of this surface call were already reported (by an earlier
    /// primitive using it).
    fn reported_surface(&mut self, s: &ShaderCall) -> bool {
        !self.surfaces_reported.insert((s.file, s.pos))
    }
}

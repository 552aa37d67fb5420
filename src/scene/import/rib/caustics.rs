//! AIR's caustics (seed 001, section 4.4) onto the caustic photon map: `LightSource
//! "caustic"` switches the map on, `Attribute "light" "nphotons"` sets its photon count and
//! `Attribute "caustic" "ngather"` its gather count; a primitive's `"caustic"`
//! `"specularcolor"`, `"refractioncolor"` and `"refractionindex"` become its material's
//! photon shader (`PhotonShaderDesc::Caustic`), and its caustic flag says what AIR's rule
//! makes of it — it casts where a colour is not black, receives where `ngather` is written,
//! and neither otherwise (the surface shader plays no part in AIR's photon tracing).
//! Without a caustic light every one of these attributes is a warning and does nothing.

use super::super::located::{Pos, Problem};
use super::build::Builder;
use super::params::Param;
use crate::scene::desc::{PhotonMapDesc, PhotonShaderDesc, SceneDesc};

impl Builder {
    /// Reads `Attribute class p` when it is one of AIR's caustic attributes (true), into the
    /// current attributes and the caustic map's counts.
    pub(super) fn air_caustic_attribute(
        &mut self,
        class: &str,
        p: &Param,
        problems: &mut Vec<Problem>,
    ) -> bool {
        let one = p.nums().len() == 1;
        let fraction = p.nums().len() == 3 && p.nums().iter().all(|x| (0.0..=1.0).contains(x));
        let caustic = &mut self.gs.attrs.caustic;
        match (class, p.name.as_str()) {
            ("light", "nphotons") if one && p.num() >= 1.0 => {
                self.photons = Some((p.num().min(f64::from(u32::MAX)) as u32, p.pos()));
            }
            ("caustic", "ngather") if one && p.num() >= 2.0 => {
                let n = p.num().min(f64::from(u32::MAX)) as u32;
                match self.gather {
                    Some((m, at)) if m != n => problems.push(Problem::warning(
                        p.pos(),
                        format!(
                            "Attribute \"caustic\" \"ngather\" {n} differs from {m} at {}:{}: \
                             stagelight gathers every caustic estimate with one count, {m}",
                            at.line, at.column
                        ),
                    )),
                    Some(_) => {}
                    None => self.gather = Some((n, p.pos())),
                }
                caustic.ngather = Some(p.pos());
            }
            ("caustic", "specularcolor") if fraction => {
                caustic.specular = Some((p.triple(), p.pos()))
            }
            ("caustic", "refractioncolor") if fraction => {
                caustic.refraction = Some((p.triple(), p.pos()));
            }
            ("caustic", "refractionindex") if one && p.num() > 0.0 => {
                caustic.ior = Some((p.num(), p.pos()));
            }
            ("caustic", "maxpixeldist") => {
                problems.push(Problem::warning(
                    p.name_pos,
                    "ignored Attribute \"caustic\" \"maxpixeldist\": stagelight bounds a caustic \
                     estimate by its photon count (ngather), not by a distance in pixels",
                ));
                return true;
            }
            // Photons see every primitive here, as AIR's `indirect` 1 asks.
            ("visibility", "indirect") if p.nums() == [1.0] => return true,
            _ => return false,
        }
        self.caustic_attributes
            .push((self.file, p.name_pos, class.to_string(), p.name.clone()));
        true
    }

    /// The photon shader the current caustic attributes give a material (`None`: none
    /// written).
    pub(super) fn photon_shader(&self) -> (Option<PhotonShaderDesc>, Vec<(String, Pos)>) {
        let c = &self.gs.attrs.caustic;
        if !c.shapes_photons() && c.ngather.is_none() {
            return (None, Vec::new());
        }
        let mut paths = Vec::new();
        let mut at = |field: &str, pos: Option<Pos>| {
            if let Some(pos) = pos {
                paths.push((format!(".photon.Caustic.{field}"), pos));
            }
        };
        at("specular", c.specular.map(|s| s.1));
        at("refraction", c.refraction.map(|s| s.1));
        at("ior", c.ior.map(|s| s.1));
        let black = (0.0, 0.0, 0.0);
        let shader = PhotonShaderDesc::Caustic {
            specular: c.specular.map_or(black, |s| s.0),
            refraction: c.refraction.map_or(black, |s| s.0),
            ior: c.ior.map_or(1.0, |s| s.0),
        };
        (Some(shader), paths)
    }

    /// The caustic map of `LightSource "caustic"`, or the warnings that the caustic
    /// attributes do nothing without it.
    pub(super) fn caustic_map(
        &mut self,
        desc: &mut SceneDesc,
        paths: &mut Vec<(String, usize, Pos)>,
    ) {
        let Some((f, p)) = self.caustics else {
            for (file, pos, class, name) in std::mem::take(&mut self.caustic_attributes) {
                let mut w = Problem::warning(
                    pos,
                    format!(
                        "ignored Attribute \"{class}\" \"{name}\": no LightSource \"caustic\" \
                         switches caustics on"
                    ),
                );
                w.help = Some(
                    "AIR renders caustics with its caustic light: add `LightSource \"caustic\" 1`"
                        .into(),
                );
                self.problems.push((file, w));
            }
            return;
        };
        let Some(o) = desc.options.as_mut() else {
            return;
        };
        let mut map = PhotonMapDesc::default();
        paths.push(("options.caustics".into(), f, p));
        if let Some((n, pos)) = self.photons {
            map.photons = n;
            paths.push(("options.caustics.photons".into(), f, pos));
        }
        if let Some((n, pos)) = self.gather {
            map.gather = n;
            paths.push(("options.caustics.gather".into(), f, pos));
        }
        o.caustics = Some(map);
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;

    fn read(text: &str) -> super::super::RibScene {
        Builder::run(Path::new("t.rib"), text.as_bytes()).unwrap_or_else(|e| panic!("{e:?}"))
    }

    const SCENE: &str = "WorldBegin\nLightSource \"caustic\" 1\n\
        AttributeBegin\nAttribute \"caustic\" \"integer ngather\" [75]\nSurface \"matte\"\n\
        Sphere 1 -1 1 360\nAttributeEnd\n\
        AttributeBegin\nAttribute \"caustic\" \"color specularcolor\" [0.4 0.4 0.4]\n\
        Attribute \"caustic\" \"float refractionindex\" [1.5]\nSphere 1 -1 1 360\nAttributeEnd\n\
        Sphere 1 -1 1 360\nWorldEnd\n";

    #[test]
    fn air_attributes_become_photon_shaders_and_caustic_flags() {
        let s = read(SCENE);
        let d = &s.desc;
        let gather = d.options.as_ref().and_then(|o| o.caustics.as_ref());
        assert_eq!(gather.map(|c| c.gather), Some(75));
        let photon = |i: usize| d.materials[i].photon.clone();
        let caustic = |specular, ior| PhotonShaderDesc::Caustic {
            specular,
            refraction: (0.0, 0.0, 0.0),
            ior,
        };
        assert_eq!(photon(0), Some(caustic((0.0, 0.0, 0.0), 1.0)));
        assert_eq!(photon(1), Some(caustic((0.4, 0.4, 0.4), 1.5)));
        assert_eq!(photon(2), None);
        // Receives (ngather), casts (a colour), neither: AIR's rule, whatever the shader.
        let flags: Vec<_> = d.instances.iter().map(|i| i.caustic).collect();
        assert_eq!(flags, [Some(2), Some(1), Some(0)]);
        let at = |p: &str| {
            s.paths
                .iter()
                .rev()
                .find(|(q, _)| q == p)
                .map(|(_, l)| l.pos)
        };
        assert_eq!(
            at("materials[1].photon.Caustic.ior"),
            Some(Pos {
                line: 10,
                column: 45
            })
        );
    }

    #[test]
    fn without_the_caustic_light_the_attributes_are_dropped() {
        let s = read(&SCENE.replace("LightSource \"caustic\" 1\n", ""));
        let d = &s.desc;
        assert!(d.options.as_ref().is_some_and(|o| o.caustics.is_none()));
        assert!(d.materials.iter().all(|m| m.photon.is_none()));
        assert!(d.instances.iter().all(|i| i.caustic.is_none()));
        let warned: Vec<_> = s
            .warnings
            .iter()
            .map(|w| (w.problem.pos.line, w.problem.message.clone()))
            .collect();
        assert_eq!(warned.len(), 3, "{warned:?}");
        assert_eq!(
            warned[0],
            (
                3,
                "ignored Attribute \"caustic\" \"ngather\": no LightSource \"caustic\" switches \
                 caustics on"
                    .into()
            )
        );
    }
}

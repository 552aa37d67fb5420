//! Feature switches (mental ray's options `lens off`, `volume off`, `geometry off`,
//! `displace off`, `output off`; RON `options.disable`; CLI `--disable lens,volume,…`): whole
//! kinds of shaders turned off for a run without editing the scene. Each is a run input read
//! by the stages that do that work (see [`Feature`]); a stage whose only work is switched off
//! is skipped with the reason "… disabled", and a stage that runs says what it leaves out.

use std::fmt;

/// One kind of shader a run can switch off.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Feature {
    /// Camera lens shaders (`shade` traces through a pinhole).
    Lens,
    /// Volume shaders: the camera's atmosphere and materials' interiors (`shade`).
    Volume,
    /// Geometry shaders and scatters (`expand_geometry` is skipped; their objects stay
    /// empty).
    Geometry,
    /// Displacement shaders: true displacement (`tessellate`) and bump displacement
    /// (`build_accel`); meshes keep their undisplaced shape.
    Displacement,
    /// Output shaders: contour drawing (`draw_contours`). Files are written as usual.
    Output,
}

impl Feature {
    /// Every feature, in the order names are listed.
    pub const ALL: [Feature; 5] = [
        Feature::Lens,
        Feature::Volume,
        Feature::Geometry,
        Feature::Displacement,
        Feature::Output,
    ];

    /// The lower-case name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Feature::Lens => "lens",
            Feature::Volume => "volume",
            Feature::Geometry => "geometry",
            Feature::Displacement => "displacement",
            Feature::Output => "output",
        }
    }

    fn bit(self) -> u8 {
        1 << self as u8
    }
}

/// A set of switched-off features (empty: everything on, the default).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct Features(u8);

impl Features {
    /// No feature switched off.
    pub const NONE: Self = Self(0);

    /// Whether `f` is switched off.
    pub fn contains(self, f: Feature) -> bool {
        self.0 & f.bit() != 0
    }

    /// Switches `f` off.
    pub fn insert(&mut self, f: Feature) {
        self.0 |= f.bit();
    }

    /// Whether nothing is switched off.
    pub fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// `self` and `other` together.
    pub fn union(self, other: Self) -> Self {
        Self(self.0 | other.0)
    }

    /// Parses a comma-separated list of feature names (`lens,volume`).
    pub fn parse_list(text: &str) -> Result<Self, String> {
        let mut set = Self::NONE;
        for word in text.split(',').map(str::trim) {
            let Some(f) = Feature::ALL.into_iter().find(|f| f.name() == word) else {
                let names: Vec<&str> = Feature::ALL.iter().map(|f| f.name()).collect();
                return Err(format!(
                    "unknown feature \"{word}\" (expected one of {})",
                    names.join(", ")
                ));
            };
            set.insert(f);
        }
        Ok(set)
    }
}

impl fmt::Display for Features {
    /// The names of the switched-off features, comma-separated.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<&str> = Feature::ALL
            .into_iter()
            .filter(|x| self.contains(*x))
            .map(Feature::name)
            .collect();
        f.write_str(&names.join(","))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_parse_and_print_in_order() {
        let set = Features::parse_list("output, lens").unwrap();
        assert!(set.contains(Feature::Lens) && set.contains(Feature::Output));
        assert!(!set.contains(Feature::Volume));
        assert_eq!(set.to_string(), "lens,output");
        assert_eq!(
            Features::parse_list("lens,fog").unwrap_err(),
            "unknown feature \"fog\" (expected one of lens, volume, geometry, displacement, output)"
        );
        assert!(Features::default().is_empty());
    }
}

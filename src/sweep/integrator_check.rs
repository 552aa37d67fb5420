//! Knobs the swept runs' integrator ignores, refused before the first run (a usage error):
//! their table would be flat, every value the same image. The path integrator samples each
//! light once per vertex, weighted by MIS, whatever the light's `samples`, and reads no
//! photon map (the reason `plan` gives for skipping `trace_photons`).

use crate::settings::Integrator;
use crate::sweep::knob::{Knob, KnobError};

/// Why the path integrator ignores `light_samples`.
const LIGHT_SAMPLES: &str = "the path integrator takes one sample of every light per vertex (weighted by multiple importance sampling), whatever the light's `samples`";

/// Why the path integrator ignores the photon-map knobs (as `plan` says for `trace_photons`).
const PHOTON_MAPS: &str = "the path integrator does not read photon maps";

/// Refuses a knob the swept runs' integrator (`--integrator`, else the scene's) ignores.
pub fn check(knob: &Knob, integrator: Integrator) -> Result<(), KnobError> {
    if integrator != Integrator::Path {
        return Ok(());
    }
    let why = match knob {
        Knob::LightSamples(_) => LIGHT_SAMPLES,
        Knob::Photons(_)
        | Knob::GatherRadius(_)
        | Knob::GatherCount(_)
        | Knob::Passes(_)
        | Knob::PhotonFilter(_) => PHOTON_MAPS,
        _ => return Ok(()),
    };
    Err(KnobError::IgnoredByPath {
        knob: knob.name(),
        why,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_path_integrator_refuses_the_knobs_it_ignores() {
        let refused = |k: &str, i| check(&Knob::parse(k).unwrap(), i).is_err();
        for k in [
            "light_samples=1,64",
            "photons=10,100",
            "passes=1,4",
            "filter=box,cone",
        ] {
            assert!(refused(k, Integrator::Path), "{k}");
            assert!(!refused(k, Integrator::Direct), "{k}");
        }
        for k in ["spp=1,4", "max_depth=1,4", "bvh_quality=fast,high"] {
            assert!(!refused(k, Integrator::Path), "{k}");
        }
        assert_eq!(
            check(&Knob::parse("gather_count=8,16").unwrap(), Integrator::Path)
                .unwrap_err()
                .to_string(),
            "knob gather_count changes nothing in the swept runs: the path integrator does not read photon maps\n  help: sweep it with `--integrator direct`, or under the path integrator sweep spp or max_depth"
        );
    }
}

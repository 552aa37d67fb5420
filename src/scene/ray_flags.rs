//! Ray flags on objects and instances (mental ray `visible`, `shadow`, `trace`): what each
//! element sets itself. They are inherited down the instance DAG exactly as the photon
//! flags are (see [`super::dag::flatten`]: the closest instance that sets a flag wins, then
//! the object's own) and carried by the placed instance as a
//! [`crate::components::RayFlags`] component when any is set.

use super::validate::Merged;
use crate::components::RayFlags;

/// The ray flags instance `inst` sets itself.
pub fn instance_ray_flags(m: &Merged<'_>, inst: usize) -> RayFlags {
    let d = m.instances[inst].desc;
    RayFlags {
        visible: d.visible,
        shadow: d.shadow,
        trace: d.trace,
    }
}

/// The ray flags object `o` sets itself.
pub fn object_ray_flags(m: &Merged<'_>, o: usize) -> RayFlags {
    let d = m.objects[o].desc;
    RayFlags {
        visible: d.visible,
        shadow: d.shadow,
        trace: d.trace,
    }
}

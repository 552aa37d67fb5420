//! Displacement shaders of `.mi` materials: the tutorial's library (seed 001 §4.4, its C
//! source printed there) is built in — after `link "myDisplacement.so"`, `displace
//! "myDisplacement" ("factor" f)` is `Sine(amplitude: 0.01, factor: f, axis: U)` on the
//! objects drawn in the material (`docs/mi.md`, the displacement paragraph).

use super::super::located::Problem;
use super::cursor::{Cursor, ShaderCall, Value};
use crate::scene::desc::{AxisDesc, ScalarDesc};

/// `displace "myDisplacement" ("factor" f)`: the tutorial's `0.01 · sin(u · f · π)` along
/// the normal (`u`: the first texture space's x), `f` 0 when not written (C's zero).
pub fn tutorial_displacement(c: &mut Cursor, call: &ShaderCall) -> Option<ScalarDesc> {
    let mut factor = 0.0;
    let mut ok = true;
    for p in &call.params {
        match (p.name.as_str(), &p.value) {
            ("factor", Value::Nums(n)) if n.len() == 1 => factor = n[0],
            ("factor", _) => {
                c.error(
                    p.value_pos,
                    "parameter \"factor\" of \"myDisplacement\" takes a number",
                );
                ok = false;
            }
            (other, _) => {
                c.report(
                    Problem::error(
                        p.pos,
                        format!("unknown parameter \"{other}\" of shader \"myDisplacement\""),
                    )
                    .with_help("its one parameter is \"factor\""),
                );
                ok = false;
            }
        }
    }
    ok.then_some(ScalarDesc::Sine {
        amplitude: 0.01,
        factor,
        axis: AxisDesc::U,
    })
}

//! mental ray's `incremental` (seed 000, `mi_api_incremental`): the changed element "is not
//! created with fresh defaults, but with the values it was created with earlier", and the
//! block applies only what it states.
//!
//! The blocks whose values are statements (`options`, `camera`, `light`, `material`, named
//! `shader`) keep what they read as tokens, [`Body`]: an incremental definition replays the
//! earlier head (the shader call) and statements before its own, so each statement it
//! writes overrides one value, and a shader call of the same shader overrides the
//! parameters it states ([`merge`]). Objects and instances start from the earlier record
//! ([`Earlier`]).

use super::cursor::{Cursor, Recorded, ShaderCall};
use super::model::{RawInstance, RawObject};
use super::statements::Reader;

/// What a statement block read, to be replayed by an `incremental` definition of it.
#[derive(Debug, Clone, Default)]
pub struct Body {
    /// The block kind (`camera`): replayed only into a block of the same kind.
    pub kind: &'static str,
    /// The head after the name (the shader call of a light, material or named shader).
    pub head: Recorded,
    /// The statements up to `end`.
    pub statements: Recorded,
}

/// The element an `incremental` definition changes, as it was.
#[derive(Debug, Clone, Default)]
pub struct Earlier {
    /// A statement block's tokens.
    pub body: Option<Body>,
    /// An object's record.
    pub object: Option<RawObject>,
    /// An instance's record.
    pub instance: Option<RawInstance>,
}

/// The earlier tokens of a `kind` block being defined incrementally (taken: `None` for a
/// fresh definition or an element of another kind).
pub fn earlier_body(r: &mut Reader, kind: &str) -> Option<Body> {
    r.earlier
        .as_mut()
        .and_then(|e| e.body.take())
        .filter(|b| b.kind == kind)
}

/// `call` changed by `next`: of the same shader, `next`'s parameters override those of
/// the same name and the others keep their values; of another shader, `next` replaces it.
pub fn merge(call: ShaderCall, next: ShaderCall) -> ShaderCall {
    if call.name != next.name {
        return next;
    }
    let mut params: Vec<_> = call
        .params
        .into_iter()
        .filter(|p| next.params.iter().all(|n| n.name != p.name))
        .collect();
    params.extend(next.params);
    ShaderCall { params, ..next }
}

/// Reads the shader call after a block's name (`what` names it in messages; `named`:
/// `= "shader"` may name a named shader). In an incremental definition (`earlier`), the
/// earlier head is replayed first and a call written here merges into it ([`merge`]); the
/// call may then be left out. Returns the call and the head's tokens.
pub fn head_call(
    r: &Reader,
    c: &mut Cursor,
    earlier: Option<&Body>,
    what: &str,
    named: bool,
) -> Option<(ShaderCall, Recorded)> {
    let start = c.index();
    let read = |c: &mut Cursor| {
        if named {
            c.shader_call_or_named(what, &r.raw.shaders)
        } else {
            c.shader_call(what)
        }
    };
    if let Some(body) = earlier {
        c.replay(&body.head);
    }
    let mut call = read(c)?;
    if earlier.is_some() {
        while c.at_string() || c.at_punct('=') {
            call = merge(call, read(c)?);
        }
    }
    Some((call, c.record(start)))
}

/// Replays the earlier statements of an incremental definition at the cursor; returns
/// the index just past them (statements read before it are the earlier ones).
pub fn replay_statements(c: &mut Cursor, earlier: Option<&Body>) -> usize {
    match earlier {
        Some(body) => c.replay(&body.statements),
        None => c.index(),
    }
}

/// Keeps a block's tokens for a later `incremental` definition of `name`.
pub fn keep(r: &mut Reader, name: &str, kind: &'static str, head: Recorded, statements: Recorded) {
    r.bodies.insert(
        name.to_string(),
        Body {
            kind,
            head,
            statements,
        },
    );
}

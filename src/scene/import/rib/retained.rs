//! Retained geometry and motion blocks.
//!
//! `ObjectBegin handle … ObjectEnd` defines an object (the handle a number or a string; a
//! handle defined again is replaced). Its primitives are kept in the object's own space,
//! with the transformations written inside the block (the definition starts at the
//! identity), and are drawn only by `ObjectInstance handle`, each time with the
//! transformation and the attributes current at the instance: RISpec 3.2 has an object
//! inherit its attributes where it is instanced, so attribute requests inside a definition
//! are located warnings. Each retained mesh becomes one object of the description, placed
//! by one instance per `ObjectInstance`; an instance whose attributes make another
//! material names it as the instance's material, one with another displacement, shading
//! rate or orientation places another object with the same mesh.
//!
//! `MotionBegin [times] … MotionEnd` holds one request per time: the first (the first time
//! sample) is read, the others are checked to be the same request and dropped. Motion blur
//! is not rendered (one warning per file, at the first block).

use std::collections::HashMap;

use glam::DMat4;

use super::super::located::{Pos, Problem};
use super::geometry::{Primitive, PRIMITIVES};
use super::parse::Request;

/// Requests read inside an object definition; every other request the reader maps is an
/// attribute or an option, which the object takes where it is instanced.
const IN_DEFINITION: &[&str] = &[
    "version",
    "Declare",
    "AttributeBegin",
    "AttributeEnd",
    "TransformBegin",
    "TransformEnd",
    "Identity",
    "Translate",
    "Rotate",
    "Scale",
    "ConcatTransform",
    "Transform",
    "Basis",
    "MotionBegin",
    "MotionEnd",
    "ObjectBegin",
    "ObjectEnd",
    "ReadArchive",
    "Procedural",
    "Procedural2",
];

/// One primitive of an object definition.
pub struct RetainedPrim {
    /// The mesh and its value positions.
    pub prim: Primitive,
    /// The transformation written inside the definition (object space ← primitive space).
    pub object_from_prim: DMat4,
    /// The request in lower case (the base of the object's name).
    pub base: String,
    /// File and position of the request.
    pub at: (usize, Pos),
    /// Objects of the description made of it so far, by displacement, shading rate and
    /// orientation.
    pub variants: HashMap<String, usize>,
}

/// An object definition being read: its handle, where it starts, its primitives.
pub struct Defining {
    /// The handle as written (numbers as `format!("{v}")`).
    pub handle: String,
    /// Where `ObjectBegin` is.
    pub pos: Pos,
    /// Its primitives so far.
    pub prims: Vec<RetainedPrim>,
}

/// The object definitions of the file.
#[derive(Default)]
pub struct Retained {
    /// Definitions by handle.
    pub defined: HashMap<String, Vec<RetainedPrim>>,
    /// The definition being read.
    pub defining: Option<Defining>,
}

impl Retained {
    /// The warning for a request that has no place inside the definition being read
    /// (`None`: read it).
    pub fn outside_definition(&self, r: &Request) -> Option<Problem> {
        let d = self.defining.as_ref()?;
        let name = r.name.as_str();
        let read = IN_DEFINITION.contains(&name)
            || PRIMITIVES.contains(&name)
            || !super::requests::MAPPED.contains(&name);
        (!read).then(|| {
            let why = if name == "ObjectInstance" {
                "an object definition cannot instance another object"
            } else {
                "an object takes its attributes where it is instanced"
            };
            Problem::warning(
                r.pos,
                format!("ignored \"{name}\" inside ObjectBegin {}: {why}", d.handle),
            )
        })
    }
}

/// A motion block being read.
pub struct Motion {
    /// Where `MotionBegin` is.
    pub pos: Pos,
    /// How many times it gives.
    pub times: usize,
    /// The request of its first sample.
    pub first: Option<String>,
    /// Requests read in it.
    pub count: usize,
    /// Whether a request other than the first was reported.
    pub mixed: bool,
}

/// What to do with a request inside a motion block.
pub enum Sample {
    /// Read it (the first sample, or not in a motion block).
    Read,
    /// Drop it (a later sample), with a problem when it is not the first sample's request.
    Drop(Option<Problem>),
}

impl Motion {
    /// Counts `r` as a sample of this block.
    pub fn sample(&mut self, r: &Request) -> Sample {
        self.count += 1;
        let Some(first) = &self.first else {
            self.first = Some(r.name.clone());
            return Sample::Read;
        };
        if *first == r.name || self.mixed {
            return Sample::Drop(None);
        }
        self.mixed = true;
        Sample::Drop(Some(Problem::error(
            r.pos,
            format!(
                "{} in the motion block of {first} opened at {}:{}: every request of a motion \
                 block must be the same",
                r.name, self.pos.line, self.pos.column
            ),
        )))
    }

    /// The problem with the block at its `MotionEnd`, if any.
    pub fn end(&self, end: Pos) -> Option<Problem> {
        (self.count != self.times && !self.mixed).then(|| {
            Problem::error(
                end,
                format!(
                    "the motion block opened at {}:{} gives {} time{} but holds {} request{}",
                    self.pos.line,
                    self.pos.column,
                    self.times,
                    if self.times == 1 { "" } else { "s" },
                    self.count,
                    if self.count == 1 { "" } else { "s" }
                ),
            )
            .with_help("write one request per time, all of the same kind")
        })
    }
}

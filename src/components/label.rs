//! An object's label: the integer the `ObjectId` pass (mental ray's `tag` output) writes
//! where the object's instances are seen.

/// On an object entity: the value of the `ObjectId` pass (`id.object`) at every pixel that
/// sees one of its instances — mental ray's object `tag`, RON's object `label`. An object
/// without one is written as 1 + the index of the placed instance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ObjectLabel(pub u32);

//! Shading library. STUB.

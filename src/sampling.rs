//! Deterministic sampling. STUB.

//! The stage table. STUB.

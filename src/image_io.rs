//! Image writers (PNG, EXR), written atomically. STUB.

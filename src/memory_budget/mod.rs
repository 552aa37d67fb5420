//! The memory budget of a run: how many bytes it may use and where that number comes from.
//! A leaf module (it imports nothing else of the crate), so the scene loader, which counts
//! image textures against the budget before decoding them, and the up-front estimates of
//! [`crate::budget`] share it.
//!
//! The default budget is the smallest of half the physical memory (`/proc/meminfo`), the
//! process's address-space limit (`ulimit -v`, `/proc/self/limits`) and its cgroup memory
//! limit (`memory.max` of cgroup v2, `memory.limit_in_bytes` of v1: what Slurm and
//! containers set); `--memory-limit BYTES` replaces it. Where none can be read, the budget
//! is unlimited.

pub mod probe;

use std::fmt;

/// A memory budget in bytes and where it comes from (for messages).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Budget {
    /// Bytes a run may use (`u64::MAX`: unlimited).
    pub bytes: u64,
    /// Where the number comes from: `--memory-limit`, `half of physical memory`, …
    pub source: String,
}

impl Budget {
    /// No limit (library callers that did not ask for one).
    pub fn unlimited() -> Self {
        Self {
            bytes: u64::MAX,
            source: "unlimited".into(),
        }
    }

    /// The limit the user gave (`--memory-limit`).
    pub fn given(bytes: u64) -> Self {
        Self {
            bytes,
            source: "--memory-limit".into(),
        }
    }

    /// The default budget of this process (see the module documentation).
    pub fn detect() -> Self {
        let mut best = Self::unlimited();
        let mut consider = |bytes: Option<u64>, source: &str| {
            if let Some(b) = bytes {
                if b < best.bytes {
                    best = Self {
                        bytes: b,
                        source: source.into(),
                    };
                }
            }
        };
        consider(
            probe::physical_memory().map(|m| m / 2),
            "half of physical memory",
        );
        consider(
            probe::address_space_limit(),
            "the address-space limit (ulimit -v)",
        );
        consider(probe::cgroup_limit(), "the cgroup memory limit");
        best
    }

    /// Whether `bytes` fit.
    pub fn fits(&self, bytes: u64) -> bool {
        bytes <= self.bytes
    }
}

impl Default for Budget {
    fn default() -> Self {
        Self::unlimited()
    }
}

impl fmt::Display for Budget {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.bytes == u64::MAX {
            f.write_str("unlimited")
        } else {
            write!(f, "{} ({})", human(self.bytes), self.source)
        }
    }
}

/// Bytes for people: `512 B`, `3.0 KiB`, `1.5 GiB`, `931.3 TiB`.
pub fn human(bytes: u64) -> String {
    const UNITS: [&str; 6] = ["B", "KiB", "MiB", "GiB", "TiB", "PiB"];
    let mut value = bytes as f64;
    let mut unit = 0;
    while value >= 1024.0 && unit + 1 < UNITS.len() {
        value /= 1024.0;
        unit += 1;
    }
    if unit == 0 {
        format!("{bytes} B")
    } else {
        format!("{value:.1} {}", UNITS[unit])
    }
}

/// Parses `--memory-limit`: bytes, optionally with a binary suffix `K`, `M`, `G`, `T`
/// (1G = 2³⁰ bytes), in any case; `KiB`… and `KB`, `MB`, `GB`, `TB` mean the same binary
/// units (as Slurm's `--mem`, Docker's `--memory` and the JVM's `-Xmx` read them). The error
/// is clap's message.
pub fn parse_bytes(text: &str) -> Result<u64, String> {
    let t = text.trim();
    let digits = t.trim_end_matches(|c: char| c.is_ascii_alphabetic());
    let suffix = t[digits.len()..].to_ascii_lowercase();
    let shift = match suffix.as_str() {
        "" | "b" => 0,
        "k" | "kb" | "kib" => 10,
        "m" | "mb" | "mib" => 20,
        "g" | "gb" | "gib" => 30,
        "t" | "tb" | "tib" => 40,
        _ => {
            return Err(format!(
                "unknown unit \"{suffix}\" (use K, M, G or T, binary: 1G = 1073741824 bytes; KB, MB, GB, TB and KiB… mean the same)"
            ))
        }
    };
    let n: u64 = digits
        .trim()
        .parse()
        .map_err(|_| "expected a number of bytes, e.g. 8G or 500000000".to_string())?;
    if n == 0 {
        return Err("the limit must be more than 0 bytes".into());
    }
    n.checked_mul(1u64 << shift)
        .ok_or_else(|| "more bytes than fit in 64 bits".to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_and_print() {
        assert_eq!(parse_bytes("1000"), Ok(1000));
        assert_eq!(parse_bytes("64M"), Ok(64 << 20));
        assert_eq!(parse_bytes("2GiB"), Ok(2 << 30));
        // Decimal-looking suffixes are the same binary units (as Slurm and Docker read them).
        assert_eq!(parse_bytes("1GB"), Ok(1 << 30));
        assert_eq!(parse_bytes("3mb"), Ok(3 << 20));
        assert_eq!(parse_bytes("2KB"), parse_bytes("2K"));
        assert_eq!(parse_bytes("1TB"), Ok(1 << 40));
        assert_eq!(
            parse_bytes("3Q"),
            Err("unknown unit \"q\" (use K, M, G or T, binary: 1G = 1073741824 bytes; KB, MB, GB, TB and KiB… mean the same)".into())
        );
        assert!(parse_bytes("0").is_err());
        assert!(parse_bytes("3Q").is_err());
        assert_eq!(human(512), "512 B");
        assert_eq!(human(3 << 10), "3.0 KiB");
        assert_eq!(human(3 << 29), "1.5 GiB");
    }

    #[test]
    fn the_detected_budget_is_finite_on_linux() {
        let b = Budget::detect();
        if std::path::Path::new("/proc/meminfo").exists() {
            assert!(b.bytes < u64::MAX, "{b}");
        }
    }
}

//! The FMU archive limits: options of the commands that open FMUs.

use clap::Args;
use fmu_import::fmu::ExtractLimits;

/// Limits on what opening one `.fmu` may unpack (against "zip bombs"); options of the commands
/// that open FMUs.
#[derive(Debug, Args)]
#[command(next_help_heading = "FMU archive limits")]
pub struct LimitArgs {
    /// Largest total size an FMU archive may unpack to, in bytes or with a K, M or G suffix
    /// (powers of 1024).
    #[arg(long, value_name = "SIZE", default_value = "2G", value_parser = parse_size)]
    pub max_unpacked_size: u64,
    /// Most entries an FMU archive may have.
    #[arg(long, value_name = "N", default_value_t = 10_000)]
    pub max_archive_entries: u64,
    /// Highest compression ratio (unpacked : packed) of any archive entry over 1 MiB.
    #[arg(long, value_name = "R", default_value_t = 200)]
    pub max_compression_ratio: u64,
}

impl LimitArgs {
    /// The extraction limits these options stand for.
    pub fn extract_limits(&self) -> ExtractLimits {
        ExtractLimits {
            max_unpacked_bytes: self.max_unpacked_size,
            max_entries: self.max_archive_entries,
            max_ratio: self.max_compression_ratio,
        }
    }
}

/// `123`, `64K`, `512M`, `2G` (binary multiples) as bytes.
fn parse_size(text: &str) -> Result<u64, String> {
    let text = text.trim();
    let (digits, shift) = match text.char_indices().last() {
        Some((at, 'K' | 'k')) => (&text[..at], 10),
        Some((at, 'M' | 'm')) => (&text[..at], 20),
        Some((at, 'G' | 'g')) => (&text[..at], 30),
        _ => (text, 0),
    };
    let number: u64 = digits.parse().map_err(|_| format!("{text:?} is not a size such as 4096, 512M or 4G"))?;
    number.checked_mul(1 << shift).ok_or_else(|| format!("{text:?} is too large"))
}

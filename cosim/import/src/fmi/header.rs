//! A plausibility check of a shared library's headers before it is loaded.
//!
//! The dynamic loader maps a library's segments as its program headers describe them; a file
//! cut short (an interrupted copy, a truncated archive entry) is mapped past its end and the
//! first touch of the missing pages kills the process with `SIGBUS`, without a message. Reading
//! the headers first turns that into an error. The checks are written by hand: a handful of
//! fixed-offset reads, with messages that say which range reaches how far.

/// Which executable format the running platform loads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// ELF (Linux and other Unix systems).
    Elf,
    /// PE/COFF (Windows DLLs).
    Pe,
    /// Not checked (macOS Mach-O: the loader validates it itself).
    Unchecked,
}

impl Format {
    /// The format of this platform's shared libraries.
    pub fn native() -> Self {
        if cfg!(windows) {
            Self::Pe
        } else if cfg!(target_os = "macos") {
            Self::Unchecked
        } else {
            Self::Elf
        }
    }
}

/// Checks `bytes`, a whole library file, against `format`; the error says why the file cannot
/// be a usable library for this platform (completing "… is not a usable shared library: ").
#[cfg(test)]
pub fn check(bytes: &[u8], format: Format) -> Result<(), String> {
    check_head(bytes, bytes.len() as u64, format)
}

/// Checks a library file of `size` bytes against `format` from its first bytes, `head`; the
/// error completes "… is not a usable shared library: ". The headers and tables (which linkers
/// put at the start) are read from `head`, the ranges they give are compared with `size`; a
/// table past `head` is not read (its entries count as empty).
pub fn check_head(head: &[u8], size: u64, format: Format) -> Result<(), String> {
    match format {
        Format::Elf => check_elf(head, size),
        Format::Pe => check_pe(head, size),
        Format::Unchecked => Ok(()),
    }
}

/// Little-endian unsigned integer of `width` bytes at `at` (`None` past the end).
fn read(bytes: &[u8], at: u64, width: usize) -> Option<u64> {
    let start = usize::try_from(at).ok()?;
    let field = bytes.get(start..start.checked_add(width)?)?;
    Some(field.iter().rev().fold(0u64, |value, byte| (value << 8) | u64::from(*byte)))
}

/// "its … reach byte N of a M-byte file (truncated?)" when `end` lies past the file.
fn within(size: u64, end: u64, what: &str) -> Result<(), String> {
    if end > size {
        return Err(format!("its {what} byte {end} of a {size}-byte file (truncated?)"));
    }
    Ok(())
}

/// The machine number of this platform in an ELF header (`e_machine`) and in a PE header
/// (`IMAGE_FILE_HEADER.Machine`); `None`: not checked.
fn native_machines() -> (Option<u64>, Option<u64>) {
    match std::env::consts::ARCH {
        "x86_64" => (Some(62), Some(0x8664)),
        "x86" => (Some(3), Some(0x14c)),
        "aarch64" => (Some(183), Some(0xaa64)),
        "arm" => (Some(40), None),
        "riscv64" => (Some(243), None),
        _ => (None, None),
    }
}

/// ELF: magic, class, byte order, type and machine, then the program header table, every
/// segment's file range and the section header table inside the file.
fn check_elf(bytes: &[u8], size: u64) -> Result<(), String> {
    if bytes.get(..4) != Some(b"\x7fELF".as_slice()) {
        return Err(format!("it does not start with the ELF magic bytes (7f 45 4c 46) ({size} bytes)"));
    }
    let wide = match bytes.get(4) {
        Some(1) => false,
        Some(2) => true,
        class => return Err(format!("its ELF class {class:?} is neither 32-bit (1) nor 64-bit (2)")),
    };
    if wide != cfg!(target_pointer_width = "64") {
        let (file, host) = if wide { (64, 32) } else { (32, 64) };
        return Err(format!("it is a {file}-bit library, this program is {host}-bit"));
    }
    if bytes.get(5) != Some(&1) {
        return Err("it is not a little-endian ELF file".to_string());
    }
    let header = if wide { 64 } else { 52 };
    within(size, header, "ELF header reaches")?;
    let field = |at32: u64, at64: u64, width32: usize| {
        if wide {
            read(bytes, at64, if width32 == 4 { 8 } else { width32 })
        } else {
            read(bytes, at32, width32)
        }
    };
    let number = |value: Option<u64>| value.unwrap_or(0);
    let kind = number(read(bytes, 16, 2));
    if kind != 3 {
        return Err(format!("its ELF type is {kind}, not a shared object (3)"));
    }
    let machine = number(read(bytes, 18, 2));
    if let Some(native) = native_machines().0.filter(|native| *native != machine) {
        return Err(format!("it is built for ELF machine {machine}, this platform is {native}"));
    }
    let (phoff, shoff) = (number(field(28, 32, 4)), number(field(32, 40, 4)));
    let (phentsize, phnum) = (number(field(42, 54, 2)), number(field(44, 56, 2)));
    let (shentsize, shnum) = (number(field(46, 58, 2)), number(field(48, 60, 2)));
    within(size, phoff.saturating_add(phentsize.saturating_mul(phnum)), "program header table reaches")?;
    let mut reach = 0u64;
    for index in 0..phnum {
        let entry = phoff + index * phentsize;
        let (offset, size) = if wide {
            (read(bytes, entry + 8, 8), read(bytes, entry + 32, 8))
        } else {
            (read(bytes, entry + 4, 4), read(bytes, entry + 16, 4))
        };
        reach = reach.max(number(offset).saturating_add(number(size)));
    }
    within(size, reach, "program headers reach")?;
    if shoff != 0 {
        within(size, shoff.saturating_add(shentsize.saturating_mul(shnum)), "section header table reaches")?;
    }
    Ok(())
}

/// PE: the DOS and PE signatures, the machine, the section table and every section's raw data
/// inside the file.
fn check_pe(bytes: &[u8], size: u64) -> Result<(), String> {
    if bytes.get(..2) != Some(b"MZ".as_slice()) {
        return Err(format!("it does not start with the DOS/PE magic bytes \"MZ\" ({size} bytes)"));
    }
    within(size, 0x40, "DOS header reaches")?;
    let pe = read(bytes, 0x3c, 4).unwrap_or(0);
    within(size, pe + 24, "PE header reaches")?;
    if read(bytes, pe, 4) != Some(0x4550) {
        return Err(format!("it has no PE signature (\"PE\\0\\0\") at byte {pe}"));
    }
    let number = |at: u64| read(bytes, at, 2).unwrap_or(0);
    let machine = number(pe + 4);
    if let Some(native) = native_machines().1.filter(|native| *native != machine) {
        return Err(format!("it is built for PE machine {machine:#x}, this platform is {native:#x}"));
    }
    let sections = pe + 24 + number(pe + 20);
    let count = number(pe + 6);
    within(size, sections + 40 * count, "section table reaches")?;
    let mut reach = 0u64;
    for index in 0..count {
        let entry = sections + 40 * index;
        let (size, offset) = (read(bytes, entry + 16, 4).unwrap_or(0), read(bytes, entry + 20, 4).unwrap_or(0));
        if size != 0 {
            reach = reach.max(offset + size);
        }
    }
    within(size, reach, "sections' raw data reach")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Why `check` refuses `bytes` as a library of `format` (it must).
    fn refusal(bytes: &[u8], format: Format) -> String {
        check(bytes, format).expect_err("refused")
    }

    /// A 64-bit little-endian ELF shared object of `size` bytes for this machine, with one
    /// segment at `offset`, `filesz` bytes long, and a section header table at `shoff`.
    fn elf(size: usize, offset: u64, filesz: u64, shoff: u64) -> Vec<u8> {
        let mut bytes = vec![0u8; size.max(128)];
        bytes[..6].copy_from_slice(b"\x7fELF\x02\x01");
        bytes[16..18].copy_from_slice(&3u16.to_le_bytes());
        bytes[18..20].copy_from_slice(&(native_machines().0.unwrap_or(62) as u16).to_le_bytes());
        bytes[32..40].copy_from_slice(&64u64.to_le_bytes());
        bytes[40..48].copy_from_slice(&shoff.to_le_bytes());
        bytes[54..56].copy_from_slice(&56u16.to_le_bytes());
        bytes[56..58].copy_from_slice(&1u16.to_le_bytes());
        bytes[58..60].copy_from_slice(&64u16.to_le_bytes());
        bytes[60..62].copy_from_slice(&2u16.to_le_bytes());
        bytes[64 + 8..64 + 16].copy_from_slice(&offset.to_le_bytes());
        bytes[64 + 32..64 + 40].copy_from_slice(&filesz.to_le_bytes());
        bytes.truncate(size);
        bytes
    }

    #[cfg(all(target_pointer_width = "64", target_arch = "x86_64"))]
    #[test]
    fn elf_ranges_are_checked() {
        assert_eq!(check(&elf(4096, 0, 4096, 3968), Format::Elf), Ok(()));
        let truncated = [
            (elf(4096, 0, 123456, 0), "its program headers reach byte 123456 of a 4096-byte file (truncated?)"),
            (elf(4096, 0, 100, 4000), "its section header table reaches byte 4128 of a 4096-byte file (truncated?)"),
            (elf(100, 0, 100, 0), "its program header table reaches byte 120 of a 100-byte file (truncated?)"),
            (elf(32, 0, 0, 0), "its ELF header reaches byte 64 of a 32-byte file (truncated?)"),
        ];
        for (bytes, why) in truncated {
            assert_eq!(refusal(&bytes, Format::Elf), why);
        }
    }

    #[cfg(all(target_pointer_width = "64", target_arch = "x86_64"))]
    #[test]
    fn elf_identity_is_checked() {
        assert_eq!(
            refusal(b"garbage!", Format::Elf),
            "it does not start with the ELF magic bytes (7f 45 4c 46) (8 bytes)"
        );
        let mut bytes = elf(4096, 0, 10, 0);
        bytes[4] = 1;
        assert_eq!(refusal(&bytes, Format::Elf), "it is a 32-bit library, this program is 64-bit");
        let mut bytes = elf(4096, 0, 10, 0);
        bytes[16] = 2;
        assert_eq!(refusal(&bytes, Format::Elf), "its ELF type is 2, not a shared object (3)");
        let mut bytes = elf(4096, 0, 10, 0);
        bytes[18] = 183;
        assert_eq!(refusal(&bytes, Format::Elf), "it is built for ELF machine 183, this platform is 62");
    }

    /// A PE file of `size` bytes for x86-64 with one section of raw data at `offset`, `raw` long.
    fn pe(size: usize, offset: u32, raw: u32) -> Vec<u8> {
        let mut bytes = vec![0u8; size.max(512)];
        bytes[..2].copy_from_slice(b"MZ");
        bytes[0x3c..0x40].copy_from_slice(&0x80u32.to_le_bytes());
        bytes[0x80..0x84].copy_from_slice(b"PE\0\0");
        bytes[0x84..0x86].copy_from_slice(&0x8664u16.to_le_bytes());
        bytes[0x86..0x88].copy_from_slice(&1u16.to_le_bytes());
        bytes[0x94..0x96].copy_from_slice(&0xf0u16.to_le_bytes());
        let section = 0x80 + 24 + 0xf0;
        bytes[section + 16..section + 20].copy_from_slice(&raw.to_le_bytes());
        bytes[section + 20..section + 24].copy_from_slice(&offset.to_le_bytes());
        bytes.truncate(size);
        bytes
    }

    #[cfg(target_arch = "x86_64")]
    #[test]
    fn pe_sections_are_checked() {
        assert_eq!(check(&pe(2048, 1024, 1024), Format::Pe), Ok(()));
        assert_eq!(
            refusal(&pe(2048, 1024, 4096), Format::Pe),
            "its sections' raw data reach byte 5120 of a 2048-byte file (truncated?)"
        );
        assert_eq!(
            refusal(&pe(300, 0, 0), Format::Pe),
            "its section table reaches byte 432 of a 300-byte file (truncated?)"
        );
        assert_eq!(refusal(b"\x7fELF", Format::Pe), "it does not start with the DOS/PE magic bytes \"MZ\" (4 bytes)");
        let mut bytes = pe(2048, 0, 0);
        bytes[0x80] = b'X';
        assert_eq!(refusal(&bytes, Format::Pe), "it has no PE signature (\"PE\\0\\0\") at byte 128");
    }

    #[test]
    fn the_native_format_of_linux_is_elf() {
        if cfg!(target_os = "linux") {
            assert_eq!(Format::native(), Format::Elf);
        }
        assert_eq!(check(b"", Format::Unchecked), Ok(()));
    }
}

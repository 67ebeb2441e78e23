//! The `autobal` executable's link (`build.rs`): position-dependent on Linux with glibc, so the
//! loader has no relative relocations to apply at start (~65 page faults a run), unless
//! `AUTOBAL_PIE=1` asked for the toolchain's default. Checked on the ELF header of the binary the
//! other tests run, independently of how it was built: its `e_type` is `ET_EXEC` (2) for a
//! position-dependent executable and `ET_DYN` (3) for a PIE.

#[test]
#[cfg(all(target_os = "linux", target_env = "gnu", not(target_feature = "crt-static")))]
fn the_executable_is_linked_at_a_fixed_address() {
    let bytes = std::fs::read(env!("CARGO_BIN_EXE_autobal")).expect("the binary the tests run");
    assert_eq!(&bytes[..4], b"\x7fELF", "an ELF file");
    // e_type: a 16-bit field at offset 16, in the file's byte order (EI_DATA at offset 5:
    // 1 = little-endian)
    let e_type = if bytes[5] == 1 { u16::from_le_bytes([bytes[16], bytes[17]]) } else { u16::from_be_bytes([bytes[16], bytes[17]]) };
    let want = if option_env!("AUTOBAL_PIE") == Some("1") { 3 } else { 2 };
    assert_eq!(e_type, want, "e_type of {} (2: fixed address, 3: PIE)", env!("CARGO_BIN_EXE_autobal"));
}

//! The `autobal` executable linked as a position-dependent executable (`-no-pie`) on Linux with
//! glibc.
//!
//! As a position-independent executable, the 16 MB binary carried ~15 000 relative relocations
//! (the panic locations' and vtables' pointers of every command, in a 268 kB `.data.rel.ro`),
//! which the loader applied at every start, writing ~65 pages before `main`: ~65 of the
//! 400-460 page faults of a `simulate` run of paper 004's passage, and 205 -> 137 faults for
//! `autobal --version` (docs/notes/benchmarks.md, "Round 3, session 15"). Linked at a fixed
//! address, the executable has none of them. The objects stay position-independent code (only
//! the final link of the binaries changes: the Python extension, a shared library built from the
//! same crates, is untouched), and shared libraries are still loaded at random addresses; what
//! is given up is the randomisation of the executable's own address (its code and statics).
//! `AUTOBAL_PIE=1` at build time keeps the toolchain's default (a PIE), e.g. for a distribution
//! whose policy requires it.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=AUTOBAL_PIE");
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let env = std::env::var("CARGO_CFG_TARGET_ENV").unwrap_or_default();
    let keep_pie = std::env::var("AUTOBAL_PIE").is_ok_and(|v| v == "1");
    // a static glibc build (`-C target-feature=+crt-static`) is linked `-static-pie` by rustc:
    // left as it is
    let crt_static = std::env::var("CARGO_CFG_TARGET_FEATURE").unwrap_or_default().split(',').any(|f| f == "crt-static");
    if os == "linux" && env == "gnu" && !keep_pie && !crt_static {
        // after rustc's own `-pie`: the C compiler driver takes the last of the two
        println!("cargo:rustc-link-arg-bins=-no-pie");
    }
}

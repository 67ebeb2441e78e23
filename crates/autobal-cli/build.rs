//! The `autobal` executable is linked without position independence on Linux with glibc
//! (`-no-pie`): a PIE executable of this size carries ~15 000 relative relocations (the
//! `.data.rel.ro` of its string and vtable tables, ~250 KB) that the dynamic loader applies
//! at every start, touching and copying those pages: ~90 of the ~420 page faults of a whole
//! `autobal simulate` run (docs/notes/benchmarks.md, "Round 3, session 9"). Only the binary's
//! link changes: the objects are compiled as before (position-independent code links into a
//! fixed-address executable), and the library target, which the Python extension links into
//! its shared object, is untouched. The cost: the executable itself is no longer loaded at a
//! random address (shared libraries, stack and heap still are).
fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let env = std::env::var("CARGO_CFG_TARGET_ENV").unwrap_or_default();
    if os == "linux" && env == "gnu" {
        println!("cargo:rustc-link-arg-bin=autobal=-no-pie");
    }
}

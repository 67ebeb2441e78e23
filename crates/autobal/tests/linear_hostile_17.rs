//! Hostile inputs to a linear rotor config (round 3, session 17; docs/reference/robustness.md,
//! "Linear rotor inputs, session 17"): each case was taken, panicked in a debug build, or was
//! reported against no key or a key the config does not have, before the fix. Each now gives
//! an error naming the key as the config spells it, and the valid neighbour of each input is
//! still read.

use autobal::linear_rotor::config::{export, linear_rotor_bytes, parse_matrix_market, LinearRotorConfig};
use autobal::linear_rotor::npz::{parse_npy, parse_npz};
use autobal::linear_rotor::shaft::{Bearing, Disk, ShaftBuilder};
use autobal::linear_rotor::{BalancerPlane, LinearRotor, Unbalance};

/// The shaft builder's config (docs/reference/config.md), `extra` appended to its element
/// table (`EL`), to `[linear_rotor]` (`TOP`) or to its balancer (`BAL`).
fn shaft(el: &str, top: &str, bal: &str) -> String {
    format!(
        "[linear_rotor]\nmodes = 2\n{top}\n[[linear_rotor.elements]]\nlength = 0.1\ne = 2.1e11\nrho = 7850.0\ncount = 6\n{el}\n\
         [[linear_rotor.disks]]\nnode = 3\nmass = 4.0\nid = 0.01\nip = 0.02\n\
         [[linear_rotor.bearings]]\nnode = 0\nk = 2e6\nc = 300.0\n[[linear_rotor.bearings]]\nnode = 6\nk = 2e6\nc = 300.0\n\
         [[linear_rotor.unbalance]]\nnode = 3\nme = 2e-4\n\
         [[linear_rotor.balancer]]\nnode = 3\nradius = 0.06\nballs = 2\nball_mass = 0.02\n{bal}\n"
    )
}

/// Read a config without files.
fn read(text: &str) -> Result<LinearRotorConfig, String> {
    let root: toml::Table = text.parse().map_err(|e| format!("toml: {e}"))?;
    linear_rotor_bytes(&root, &mut |p| Err(format!("{p}: no files here"))).map_err(|e| e.to_string())
}

/// The error of `text`, which must start with `field: `.
fn refused(text: &str, field: &str) -> String {
    let e = read(text).map(|_| ()).expect_err(field);
    assert!(e.starts_with(&format!("{field}: ")), "expected an error naming {field}, got: {e}");
    assert!(!e.contains('\n'), "one line: {e}");
    e
}

const DIA: &str = "diameter = 0.025";

#[test]
fn the_valid_neighbours_are_read() {
    read(&shaft(DIA, "", "drag = 0.1")).unwrap();
    read(&shaft(&format!("{DIA}\ng_s = 8e10"), "", "")).unwrap();
    read(&shaft(&format!("{DIA}\ng_s = 8e10\nkappa = 0.9"), "", "")).unwrap();
    read(&shaft("area = 4.9e-4\ninertia = 1.9e-8", "", "")).unwrap();
    read(&shaft(DIA, "gravity = [0.0, -9.81]\npolar_inertia = 0.02\nspin_damping = 0.1", "rolling_resistance = 1e-3")).unwrap();
    // more pairs than the interior has: all of them (reduce's documented rule), not an error
    read(&shaft(DIA, "", "").replace("modes = 2\n", "modes = 2000\n")).unwrap();
}

/// `inner_diameter` beside `area` and `inertia` was silently ignored (the section was theirs).
#[test]
fn inner_diameter_with_area_and_inertia_is_refused() {
    let e = refused(&shaft("area = 4.9e-4\ninertia = 1.9e-8\ninner_diameter = 0.01", "", ""), "linear_rotor.elements[0].inner_diameter");
    assert!(e.contains("goes with diameter"), "{e}");
}

/// A shear modulus or coefficient that made the Timoshenko element's shear stiffness or shear
/// parameter non-finite was reported against `elements[0].shear` (no key of the config) or as
/// `linear_rotor.m[0,0]: NaN`; `g_s` and `kappa` now have ranges, and Φ is checked.
#[test]
fn shear_modulus_and_coefficient_are_bounded_and_named() {
    for (el, field) in [
        ("g_s = 1e-300", "linear_rotor.elements[0].g_s"),
        ("g_s = 1e300", "linear_rotor.elements[0].g_s"),
        ("g_s = 8e10\nkappa = 1e-300", "linear_rotor.elements[0].kappa"),
        ("g_s = 8e10\nkappa = 1e300", "linear_rotor.elements[0].kappa"),
    ] {
        let e = refused(&shaft(&format!("{DIA}\n{el}"), "", ""), field);
        assert!(!e.contains(".shear:") && !e.contains("linear_rotor.m"), "{e}");
    }
}

/// `gravity = [0, -1e300]` ran (stability: "stable: nowhere", every speed's integration
/// non-finite); a NaN in `gravity_load` was named `linear_rotor.gravity.load[0]`.
#[test]
fn gravity_is_bounded_and_its_load_named_as_the_config_spells_it() {
    let e = refused(&shaft(DIA, "gravity = [0.0, -1e300]", ""), "linear_rotor.gravity[1]");
    assert!(e.contains("[-1e6, 1e6] m/s²"), "{e}");
    let load = format!("gravity = [0.0, -9.81]\ngravity_load = [nan{}]", ", 0.0".repeat(27));
    refused(&shaft(DIA, &load, ""), "linear_rotor.gravity_load[0]");
}

/// `polar_inertia = 1e300` was taken; `spin_damping = 1e300` ended a torque-driven run at t = 0
/// with "the step size fell to 0", naming no key.
#[test]
fn polar_inertia_and_spin_damping_are_bounded() {
    refused(&shaft(DIA, "polar_inertia = 1e300", ""), "linear_rotor.polar_inertia");
    refused(&shaft(DIA, "spin_damping = 1e300", ""), "linear_rotor.spin_damping");
}

/// A balancer's `drag = 1e300` ran to "neutral at every speed"; `rolling_resistance = -1` was
/// taken as none (the plane's real-ball physics inactive, so never checked);
/// `contact_stiffness = 1e300` ran.
#[test]
fn balancer_keys_have_the_planar_rotors_ranges() {
    for (bal, field) in [
        ("drag = 1e300", "drag"),
        ("rolling_resistance = -1.0", "rolling_resistance"),
        ("contact = true\ncontact_stiffness = 1e300", "contact_stiffness"),
        ("contact = true\nball_diameter = 1e300", "ball_diameter"),
    ] {
        refused(&shaft(DIA, "", bal), &format!("linear_rotor.balancer[0].{field}"));
    }
}

/// `modes = 99999999999` was taken (the sweep path `linear_rotor.modes` stops at 2000).
#[test]
fn modes_is_bounded_as_its_path() {
    let text = shaft(DIA, "", "").replace("modes = 2\n", "modes = 99999999999\n");
    let e = refused(&text, "linear_rotor.modes");
    assert!(e.contains("between 0 and 2000"), "{e}");
}

/// A `.npy` array of the `n × n` row-major `a` (format 1.0, `<f8`, C order), `extra` bytes after.
fn npy(a: &[f64], n: usize, extra: usize) -> Vec<u8> {
    let mut h = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({n}, {n}), }}");
    while !(10 + h.len() + 1).is_multiple_of(64) {
        h.push(' ');
    }
    h.push('\n');
    let mut b = b"\x93NUMPY\x01\x00".to_vec();
    b.extend_from_slice(&(h.len() as u16).to_le_bytes());
    b.extend_from_slice(h.as_bytes());
    for v in a {
        b.extend_from_slice(&v.to_le_bytes());
    }
    b.extend(std::iter::repeat_n(0u8, extra));
    b
}

/// A `.npy` file longer than its header announces was read up to the announced size: a header
/// that understates the shape gave a matrix of the array's first entries.
#[test]
fn npy_bytes_past_the_announced_data_are_refused() {
    let a = [2.0, 0.0, 0.0, 3.0];
    assert!(parse_npy(&npy(&a, 2, 0)).is_ok());
    let e = parse_npy(&npy(&a, 2, 16)).unwrap_err();
    assert!(e.contains("48 bytes of data, the header announces 32"), "{e}");
}

/// ZIP offsets pointing past the archive's end (2⁶⁴ − 1 in a ZIP64 record or locator) were
/// added to without a check: a panic ("attempt to add with overflow") in a debug build.
#[test]
fn npz_offsets_past_the_end_are_errors_not_panics() {
    let eocd = |cd: u32| {
        let mut e = vec![0x50, 0x4b, 0x05, 0x06, 0, 0, 0, 0, 0xff, 0xff, 0xff, 0xff, 0, 0, 0, 0];
        e.extend_from_slice(&cd.to_le_bytes());
        e.extend_from_slice(&[0, 0]);
        e
    };
    // ZIP64 locator naming a record at 2⁶⁴ − 1
    let mut z = vec![0x50, 0x4b, 0x06, 0x07, 0, 0, 0, 0];
    z.extend_from_slice(&u64::MAX.to_le_bytes());
    z.extend_from_slice(&1u32.to_le_bytes());
    z.extend(eocd(0xFFFF_FFFF));
    let e = parse_npz(&z).unwrap_err();
    assert!(e.contains("lies past its end"), "{e}");
    // a ZIP64 record naming the central directory at 2⁶⁴ − 2
    let mut rec = vec![0x50, 0x4b, 0x06, 0x06];
    rec.extend_from_slice(&44u64.to_le_bytes());
    rec.extend_from_slice(&[45, 0, 45, 0, 0, 0, 0, 0, 0, 0, 0, 0]);
    rec.extend_from_slice(&1u64.to_le_bytes());
    rec.extend_from_slice(&1u64.to_le_bytes());
    rec.extend_from_slice(&0u64.to_le_bytes());
    rec.extend_from_slice(&(u64::MAX - 1).to_le_bytes());
    let mut z = rec;
    z.extend_from_slice(&[0x50, 0x4b, 0x06, 0x07, 0, 0, 0, 0]);
    z.extend_from_slice(&0u64.to_le_bytes());
    z.extend_from_slice(&1u32.to_le_bytes());
    z.extend(eocd(0xFFFF_FFFF));
    let e = parse_npz(&z).unwrap_err();
    assert!(e.contains("central directory lies past its end"), "{e}");
}

/// The array format's size `10000000000 10000000000` was multiplied before the size was
/// checked: a panic ("attempt to multiply with overflow") in a debug build.
#[test]
fn matrix_market_array_size_is_checked_before_its_product() {
    for sym in ["general", "symmetric", "skew-symmetric"] {
        let e = parse_matrix_market(&format!("%%MatrixMarket matrix array real {sym}\n10000000000 10000000000\n1\n")).unwrap_err();
        assert!(e.contains("outside 1..2000"), "{e}");
    }
    assert_eq!(parse_matrix_market("%%MatrixMarket matrix array real symmetric\n2 2\n1\n0.5\n3\n").unwrap(), (2, 2, vec![1.0, 0.5, 0.5, 3.0]));
}

/// CRC-32 (IEEE, as ZIP).
fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in data {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
        }
    }
    !crc
}

/// A ZIP archive of stored members (as `np.savez` writes them, without ZIP64).
fn zip(members: &[(&str, &[u8])]) -> Vec<u8> {
    let (mut out, mut cd) = (vec![], vec![]);
    for (name, data) in members {
        let (offset, crc, len) = (out.len() as u32, crc32(data), data.len() as u32);
        out.extend_from_slice(&[0x50, 0x4b, 0x03, 0x04, 20, 0, 0, 0, 0, 0, 0, 0, 0, 0]);
        out.extend_from_slice(&crc.to_le_bytes());
        out.extend_from_slice(&len.to_le_bytes());
        out.extend_from_slice(&len.to_le_bytes());
        out.extend_from_slice(&(name.len() as u16).to_le_bytes());
        out.extend_from_slice(&[0, 0]);
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(data);
        cd.extend_from_slice(&[0x50, 0x4b, 0x01, 0x02, 20, 0, 20, 0, 0, 0, 0, 0, 0, 0, 0, 0]);
        cd.extend_from_slice(&crc.to_le_bytes());
        cd.extend_from_slice(&len.to_le_bytes());
        cd.extend_from_slice(&len.to_le_bytes());
        cd.extend_from_slice(&(name.len() as u16).to_le_bytes());
        cd.extend_from_slice(&[0; 12]);
        cd.extend_from_slice(&offset.to_le_bytes());
        cd.extend_from_slice(name.as_bytes());
    }
    let (cd_at, cd_len, n) = (out.len() as u32, cd.len() as u32, members.len() as u16);
    out.extend(cd);
    out.extend_from_slice(&[0x50, 0x4b, 0x05, 0x06, 0, 0, 0, 0]);
    out.extend_from_slice(&n.to_le_bytes());
    out.extend_from_slice(&n.to_le_bytes());
    out.extend_from_slice(&cd_len.to_le_bytes());
    out.extend_from_slice(&cd_at.to_le_bytes());
    out.extend_from_slice(&[0, 0]);
    out
}

/// A small rotor from matrix files: `(the config's [linear_rotor] text without the matrices,
/// n, M, K)`.
fn small() -> (String, usize, Vec<f64>, Vec<f64>) {
    let mut b = ShaftBuilder::uniform(4, 0.4, 0.02, 2.1e11, 7850.0);
    b.disks.push(Disk { node: 2, mass: 1.0, id: 1e-3, ip: 2e-3 });
    b.bearings.push(Bearing { node: 0, k: 1e6, c: 30.0 });
    b.bearings.push(Bearing { node: 4, k: 1e6, c: 30.0 });
    let mut r: LinearRotor = b.build().unwrap();
    r.unbalances.push(Unbalance { node: 2, me: 1e-4, phase: 0.0, offset: 0.0 });
    r.balancers.push(BalancerPlane { node: 2, radius: 0.05, balls: 2, ball_mass: 0.01, drag: 0.01, offset: 0.0 });
    let (text, _) = export(&r, "r");
    let rest: String = text.lines().filter(|l| !["m = ", "c = ", "g = ", "k = "].iter().any(|k| l.starts_with(k))).map(|l| format!("{l}\n")).collect();
    (rest, r.dofs(), r.m, r.k)
}

fn read_with(text: &str, files: &[(&str, Vec<u8>)]) -> Result<LinearRotorConfig, String> {
    let root: toml::Table = text.parse().map_err(|e| format!("toml: {e}"))?;
    linear_rotor_bytes(&root, &mut |p| files.iter().find(|f| f.0 == p).map(|f| f.1.clone()).ok_or(format!("{p}: missing"))).map_err(|e| e.to_string())
}

/// A matrix file named by the empty string (`rotor_fixed_mass = ""`) said
/// "linear_rotor.rotor_fixed_mass: : : cannot read: …" (session 28's hunt): the empty name is
/// said as such, for every file key and the archive.
#[test]
fn an_empty_file_name_is_said_to_be_empty() {
    let (rest, n, m, k) = small();
    let files = [("M.npy", npy(&m, n, 0)), ("K.npy", npy(&k, n, 0))];
    let with = |extra: &str| rest.replacen("[linear_rotor]\n", &format!("[linear_rotor]\n{extra}"), 1);
    read_with(&with("m = \"M.npy\"\nk = \"K.npy\"\n"), &files).unwrap();
    for (extra, key) in [
        ("m = \"M.npy\"\nk = \"K.npy\"\nrotor_fixed_mass = \"\"\n", "linear_rotor.rotor_fixed_mass"),
        ("m = \"\"\nk = \"K.npy\"\n", "linear_rotor.m"),
        ("m = \"M.npy\"\nk = \" \"\n", "linear_rotor.k"),
        ("matrices = \"\"\n", "linear_rotor.matrices"),
    ] {
        let e = read_with(&with(extra), &files).map(|_| ()).unwrap_err();
        assert!(e.starts_with(&format!("{key}: the file name is empty (")) && !e.contains(": : "), "{e}");
    }
}

/// An `.npz` archive with two members for one array (`K` beside `k`, or `K.npy` twice) was
/// read with the first and the other silently ignored.
#[test]
fn npz_members_for_one_array_twice_are_refused() {
    let (rest, n, m, k) = small();
    let text = rest.replacen("[linear_rotor]\n", "[linear_rotor]\nmatrices = \"r.npz\"\n", 1);
    let (mb, kb, k2) = (npy(&m, n, 0), npy(&k, n, 0), npy(&k.iter().map(|v| 2.0 * v).collect::<Vec<_>>(), n, 0));
    read_with(&text, &[("r.npz", zip(&[("M.npy", &mb), ("K.npy", &kb)]))]).unwrap();
    for (second, named) in [("k.npy", "\"k\""), ("K.npy", "\"K\"")] {
        let e = read_with(&text, &[("r.npz", zip(&[("M.npy", &mb), ("K.npy", &kb), (second, &k2)]))]).map(|_| ()).unwrap_err();
        assert!(e.starts_with("linear_rotor.matrices: r.npz: members \"K\" and ") && e.contains(named), "{e}");
    }
}

/// `M` times 1e300 or 1e-300 in a matrix file was reported as "the eigenvalue iteration did not
/// converge at Ω = 0", naming no key (by `stability`); the entries are bounded now.
#[test]
fn matrix_entries_beyond_any_rotors_are_refused_by_key() {
    let (rest, n, m, k) = small();
    let text = rest.replacen("[linear_rotor]\n", "[linear_rotor]\nm = \"M.npy\"\nk = \"K.npy\"\n", 1);
    let kb = npy(&k, n, 0);
    read_with(&text, &[("M.npy", npy(&m, n, 0)), ("K.npy", kb.clone())]).unwrap();
    for (factor, says) in [(1e300, "beyond ±1e100"), (1e-300, "below 1e-100")] {
        let scaled: Vec<f64> = m.iter().map(|v| v * factor).collect();
        let e = read_with(&text, &[("M.npy", npy(&scaled, n, 0)), ("K.npy", kb.clone())]).map(|_| ()).unwrap_err();
        assert!(e.starts_with("linear_rotor.m: ") && e.contains(says), "{e}");
    }
    // Matrix Market too
    let mtx = format!("%%MatrixMarket matrix coordinate real general\n{n} {n} 1\n1 1 1e300\n");
    let text = text.replace("M.npy", "M.mtx");
    let e = read_with(&text, &[("M.mtx", mtx.into_bytes()), ("K.npy", kb)]).map(|_| ()).unwrap_err();
    assert!(e.starts_with("linear_rotor.m: M.mtx: entry [0, 0] is 1e300, beyond ±1e100"), "{e}");
}

//! The capacitance entries `s v_rᵀ A⁻¹ĝ_q` of the coupling groups
//! ([`contact_update`](super::contact_update)), kept while their inputs are the same bit for
//! bit (issue #10, performance).
//!
//! Within a time step, the vectors v of every wheel are fixed by the step's geometry (the mode
//! shapes under the wheel and the wheel's own DOF), and a point contact's ĝ is too (−w(x_k)
//! and the wheel's DOF), so the extrapolated start and the iterations of a step form the same
//! entries for the wheels on the span. A group's entries are therefore kept with what they
//! were formed from: the group's wheels in order, per wheel the identity of its A⁻¹ĝ (a new
//! one at every fresh solve, `CapacitanceWork::start_wheel`; a reused A⁻¹ĝ is the same vector)
//! and of its v (a new one whenever v on its pattern changes, compared bit for bit, or the
//! step attempt's when the caller declares v fixed by its geometry,
//! [`CapacitanceWork::new_geometry`]), and s. A
//! kept entry is the value the same dot product would give again (same inputs, same
//! operations): the update is unchanged bit for bit (tested in `tests/vehicle_bridge_linalg.rs`
//! and by the bit-for-bit crossing with every car coupled, docs/trains.md).

use super::{CapacitanceWork, SolveKey, pattern_dot};

/// One group's kept entries.
#[derive(Debug, Default)]
pub(super) struct GroupEntries {
    /// The group's wheels in order, with the identities of their (A⁻¹ĝ, v).
    wheels: Vec<usize>,
    ids: Vec<(u64, u64)>,
    /// s, bit for bit.
    s: u64,
    /// `s v_rᵀ A⁻¹ĝ_q`, row-major over the group's wheels.
    entries: Vec<f64>,
}

/// The kept entries of every coupling group of the last updates, and the identities of the
/// wheels' v.
#[derive(Debug, Default)]
pub(super) struct EntryCache {
    /// Per wheel: v on its pattern as last seen (in `SolveKey::g`), and its identity.
    v_key: Vec<SolveKey>,
    v_id: Vec<u64>,
    next_id: u64,
    /// The geometry declared by [`CapacitanceWork::new_geometry`] (0: none, compare v), and
    /// the number of geometries declared.
    geometry: u64,
    geometries: u64,
    /// Per group position in an update.
    groups: Vec<GroupEntries>,
    /// The identities of the group being formed (scratch).
    ids: Vec<(u64, u64)>,
    /// Check the declared geometry's contract ([`CapacitanceWork::verify_declared_geometry`];
    /// always in debug builds), and per wheel the geometry and v it was last checked with.
    verify: bool,
    declared: Vec<(u64, SolveKey)>,
    /// Entries kept and formed (statistics for tests).
    pub(super) kept: u64,
    pub(super) formed: u64,
}

impl EntryCache {
    /// The entries of group `g` from the last [`CapacitanceWork::group_entries`], row-major.
    pub(super) fn of_group(&self, g: usize) -> &[f64] {
        &self.groups[g].entries
    }

    /// The identity of wheel `wheel`'s v: the declared geometry's (odd), or one found by
    /// comparing v on `pattern` with the last v seen (even; a new one if it changed).
    fn v_identity(&mut self, wheel: usize, v: &[f64], pattern: &[usize]) -> u64 {
        if self.geometry != 0 {
            if self.verify || cfg!(debug_assertions) {
                self.check_declared(wheel, v, pattern);
            }
            return (self.geometry << 1) | 1;
        }
        if self.v_key.len() <= wheel {
            self.v_key.resize_with(wheel + 1, SolveKey::default);
            self.v_id.resize(wheel + 1, 0);
        }
        // The key's version is 1 for a stored v (0: nothing stored).
        if !self.v_key[wheel].matches(1, v, pattern) {
            self.v_key[wheel].set(1, v, pattern);
            self.next_id += 1;
            self.v_id[wheel] = self.next_id << 1;
        }
        self.v_id[wheel]
    }

    /// Panics if wheel `wheel`'s v on `pattern` differs, in any bit, from the v it had at its
    /// first use under the declared geometry (the caller's contract,
    /// [`CapacitanceWork::new_geometry`]): a programming error that would give wrong
    /// capacitance entries.
    fn check_declared(&mut self, wheel: usize, v: &[f64], pattern: &[usize]) {
        if self.declared.len() <= wheel {
            self.declared.resize_with(wheel + 1, Default::default);
        }
        let (geometry, key) = &mut self.declared[wheel];
        if *geometry != self.geometry {
            *geometry = self.geometry;
            key.set(1, v, pattern);
        } else {
            assert!(
                key.matches(1, v, pattern),
                "CapacitanceWork::new_geometry: wheel {wheel}'s v changed within a declared geometry (v must be fixed until the next declaration)"
            );
        }
    }
}

impl CapacitanceWork {
    /// The entries `s v_rᵀ A⁻¹ĝ_q` of group `g` (its members are `order[range]`, positions in
    /// `active`), kept from an earlier update when formed from the same inputs (module
    /// documentation) or formed now; returns them row-major.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn group_entries(
        &mut self,
        g: usize,
        range: std::ops::Range<usize>,
        active: &[usize],
        s: f64,
        v: &[impl AsRef<[f64]>],
        pattern: &[impl AsRef<[usize]>],
    ) {
        let cache = &mut self.entries;
        cache.ids.clear();
        for &c in &self.order[range.clone()] {
            let wheel = active[c];
            let v_id = cache.v_identity(wheel, v[wheel].as_ref(), pattern[wheel].as_ref());
            cache.ids.push((self.g_id[wheel], v_id));
        }
        if cache.groups.len() <= g {
            cache.groups.resize_with(g + 1, GroupEntries::default);
        }
        let kept = &mut cache.groups[g];
        let members = &self.order[range];
        let same = kept.s == s.to_bits()
            && kept.ids == cache.ids
            && kept.wheels.len() == members.len()
            && kept
                .wheels
                .iter()
                .zip(members)
                .all(|(&w, &c)| w == active[c]);
        if same {
            cache.kept += 1;
            return;
        }
        cache.formed += 1;
        kept.s = s.to_bits();
        kept.ids.clone_from(&cache.ids);
        kept.wheels.clear();
        kept.wheels.extend(members.iter().map(|&c| active[c]));
        kept.entries.clear();
        for &cr in members {
            let (pr, vr) = (pattern[active[cr]].as_ref(), v[active[cr]].as_ref());
            for &cq in members {
                let y = &self.ainv_g[active[cq]];
                kept.entries.push(s * pattern_dot(pr, vr, y));
            }
        }
    }

    /// Declares a new geometry: every wheel's v passed to the following updates, until the
    /// next declaration, is the same on its pattern bit for bit (v fixed by the wheel
    /// positions of a step attempt: declared once per attempt), so v is not compared. Without
    /// a declaration (the default) each v is compared with the last one seen. A declaration
    /// that does not hold gives wrong capacitance entries: only for callers that write v from
    /// the geometry alone.
    ///
    /// The contract is checked in debug builds, and in any build after
    /// [`Self::verify_declared_geometry`]: each wheel's v is then compared with its v at its
    /// first use under the declaration (a panic names the wheel if it differs).
    pub fn new_geometry(&mut self) {
        self.entries.geometries += 1;
        self.entries.geometry = self.entries.geometries;
    }

    /// Checks the contract of [`Self::new_geometry`] at run time (`true`; it costs a
    /// comparison of v per wheel and update, as without a declaration), or only in debug builds
    /// (`false`, the default).
    pub fn verify_declared_geometry(&mut self, on: bool) {
        self.entries.verify = on;
    }

    /// The capacitance groups whose entries were kept and formed so far (statistics).
    pub fn entry_counts(&self) -> (u64, u64) {
        (self.entries.kept, self.entries.formed)
    }
}

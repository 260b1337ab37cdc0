//! The coupling groups of a contact update ([`contact_update`](super::contact_update)):
//! the active wheels whose A⁻¹ĝ touch a common block of A, by union–find, kept from one update
//! to the next while formed from the same wheels and blocks (issue #10, performance).

use super::CapacitanceWork;

/// What the coupling groups of the last update were formed from: the active wheels, the
/// identities of their A⁻¹ĝ (`CapacitanceWork::g_id`, new at every fresh solve, the only
/// place that writes a wheel's blocks of A) and A's version. The groups are a function of the
/// active wheels' blocks, so the same key gives the same groups (issue #10, performance: the
/// iterations of a step meet the groups of its extrapolated start).
#[derive(Debug, Default)]
pub(super) struct GroupsKey {
    /// A key is stored (cleared when the wheels' storage or A's block count changes, and by
    /// an update that folded wheels: its groups leave the folded ones out).
    pub(super) valid: bool,
    version: u64,
    active: Vec<usize>,
    ids: Vec<u64>,
}

impl GroupsKey {
    pub(super) fn matches(&self, version: u64, active: &[usize], g_id: &[u64]) -> bool {
        self.valid
            && self.version == version
            && self.active == active
            && self.ids.iter().zip(active).all(|(&id, &k)| id == g_id[k])
    }

    pub(super) fn set(&mut self, version: u64, active: &[usize], g_id: &[u64]) {
        self.valid = true;
        self.version = version;
        self.active.clear();
        self.active.extend_from_slice(active);
        self.ids.clear();
        self.ids.extend(active.iter().map(|&k| g_id[k]));
    }
}

impl CapacitanceWork {
    /// The coupling groups of the wheels `active` (positions in it, the folded ones left out
    /// if `folding`) into `order` and `group_start`: union–find over the blocks of A that
    /// their A⁻¹ĝ touch.
    pub(super) fn form_groups(&mut self, active: &[usize], folding: bool) {
        let k = active.len();
        let update = self.next_stamp();
        self.parent.clear();
        self.parent.extend(0..k);
        for c in 0..k {
            if folding && self.folded[c] {
                continue;
            }
            // The wheel last joined (the wheels on the span meet the same first wheel on every
            // mode block: one union is enough).
            let mut joined = usize::MAX;
            for &b in &self.blocks[active[c]] {
                let (seen, first) = self.first[b];
                if seen == update {
                    if first == joined {
                        continue;
                    }
                    joined = first;
                    let (ra, rb) = (find(&mut self.parent, c), find(&mut self.parent, first));
                    if ra != rb {
                        self.parent[ra.max(rb)] = ra.min(rb);
                    }
                } else {
                    self.first[b] = (update, c);
                }
            }
        }
        // Group the wheels (stable: by root, then position; roots are the smallest member).
        self.order.clear();
        self.group_start.clear();
        for c in 0..k {
            let root = find(&mut self.parent, c);
            self.parent[c] = root;
        }
        for root in 0..k {
            if self.parent[root] != root || (folding && self.folded[root]) {
                continue;
            }
            self.group_start.push(self.order.len());
            for c in root..k {
                if self.parent[c] == root {
                    self.order.push(c);
                }
            }
        }
        self.group_start.push(self.order.len());
    }
}

/// The root of `a` in the union–find forest `parent` (with path halving).
fn find(parent: &mut [usize], mut a: usize) -> usize {
    while parent[a] != a {
        parent[a] = parent[parent[a]];
        a = parent[a];
    }
    a
}

//! Longest first: the passages of a sweep handed to the cores one at a time, the costliest
//! first (issue #12, performance).
//!
//! The passages of an interaction sweep differ in cost by a factor of about six (HSLM-A1 at
//! 140 km/h against HSLM-A10 at 420 km/h: its coupled steps times its wheels). Cut into fixed
//! halves, or stolen half-ranges as a parallel iterator does, the last passages to finish may
//! be long ones and leave a core idle for their duration. Here every worker takes the next
//! passage from one list sorted by decreasing estimated cost (the LPT rule of list scheduling,
//! Graham 1969, references.md §R4.6: its makespan is at most 4/3 − 1/(3P) of the optimum on P
//! processors), so the passages that finish last are the short ones.
//!
//! The order in which passages run changes no result: each passage is computed on its own and
//! stored at its own index.

use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;

/// The indices `0..cost.len()` by decreasing cost; ties (and non-finite costs, placed last) in
/// increasing index.
pub fn longest_first(cost: &[f64]) -> Vec<usize> {
    let key = |i: usize| {
        if cost[i].is_finite() {
            cost[i]
        } else {
            f64::NEG_INFINITY
        }
    };
    let mut order: Vec<usize> = (0..cost.len()).collect();
    order.sort_by(|&a, &b| key(b).total_cmp(&key(a)).then(a.cmp(&b)));
    order
}

/// `job(work, i)` for every `i` in `order`, on the current rayon pool: each worker (with its own
/// `init()` work space) takes the next index of `order` until none is left. Returns the results
/// indexed by job (`out[i]` is job `i`'s), whatever the number of threads.
pub fn run_in_order<W, T: Send>(
    order: &[usize],
    init: impl Fn() -> W + Sync,
    job: impl Fn(&mut W, usize) -> T + Sync,
) -> Vec<T> {
    let next = AtomicUsize::new(0);
    let workers = rayon::current_num_threads().clamp(1, order.len().max(1));
    let mut done: Vec<(usize, T)> = (0..workers)
        .into_par_iter()
        .flat_map_iter(|_| {
            let mut work = init();
            let mut out = Vec::new();
            loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                let Some(&i) = order.get(k) else { break };
                out.push((i, job(&mut work, i)));
            }
            out
        })
        .collect();
    done.sort_by_key(|&(i, _)| i);
    done.into_iter().map(|(_, t)| t).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Decreasing cost, ties and NaN in index order.
    #[test]
    fn longest_first_sorts_by_decreasing_cost() {
        assert_eq!(
            longest_first(&[1.0, 3.0, f64::NAN, 3.0, 2.0]),
            vec![1, 3, 4, 0, 2]
        );
        assert!(longest_first(&[]).is_empty());
    }

    /// Every job runs exactly once and its result lands at its index, for 1, 2 and 3 threads
    /// and any order.
    #[test]
    fn results_are_indexed_by_job_for_any_thread_count() {
        let n = 37;
        let cost: Vec<f64> = (0..n).map(|i| ((i * 7919) % 13) as f64).collect();
        let order = longest_first(&cost);
        let reference: Vec<usize> = (0..n).map(|i| i * i).collect();
        for threads in 1..=3 {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let out = pool.install(|| {
                run_in_order(
                    &order,
                    || 0usize,
                    |calls, i| {
                        *calls += 1;
                        i * i
                    },
                )
            });
            assert_eq!(out, reference, "{threads} threads");
        }
    }
}

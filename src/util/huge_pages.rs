//! An allocator that backs large allocations with 2 MiB pages where the system allows it.
//!
//! A step of the engine sweeps every particle's state, its neighbour list and contact
//! history, tens of megabytes on a bed of 50 000 spheres. With the processor's usual 4 KiB
//! pages that is more pages than its address-translation cache holds, so most sweeps pay a
//! page-table walk every few cache lines. Linux keeps such memory on transparent huge pages
//! only where the program asks (`/sys/kernel/mm/transparent_hugepage/enabled` = `madvise`,
//! the common default): this allocator asks for allocations of at least [`LARGE`] bytes,
//! aligned to a huge page, and advises only the allocation itself, so the kernel backs its
//! whole huge pages and nothing beyond it (no memory is added). Smaller allocations go to
//! the system allocator unchanged.
//! Results do not depend on it: only where memory sits changes. `REGOLITH_NO_HUGE_PAGES=1`
//! leaves the advice out (to measure what it brings).

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicU8, Ordering};

/// Whether to advise huge pages: 0 not yet read from the environment, 1 yes, 2 no.
static ADVISE: AtomicU8 = AtomicU8::new(0);

/// Is the advice wanted (`REGOLITH_NO_HUGE_PAGES` unset)? Read once, without allocating.
fn wanted() -> bool {
    match ADVISE.load(Ordering::Relaxed) {
        1 => true,
        2 => false,
        _ => {
            // SAFETY: a NUL-terminated name; getenv neither allocates nor keeps the pointer
            let off = unsafe { !libc::getenv(c"REGOLITH_NO_HUGE_PAGES".as_ptr()).is_null() };
            ADVISE.store(if off { 2 } else { 1 }, Ordering::Relaxed);
            !off
        }
    }
}

/// Allocations of at least this many bytes (2 MiB, one huge page) are put on huge pages.
pub const LARGE: usize = 2 << 20;

/// The huge page size this allocator aligns large allocations to (bytes).
pub const HUGE_PAGE: usize = 2 << 20;

/// The system allocator, with large allocations on transparent huge pages (see the module).
#[derive(Debug, Default, Clone, Copy)]
pub struct HugePages;

impl HugePages {
    /// The layout a request of `layout` is served with: aligned to a huge page when large.
    fn served(layout: Layout) -> Layout {
        if layout.size() >= LARGE && layout.align() < HUGE_PAGE {
            Layout::from_size_align(layout.size(), HUGE_PAGE).unwrap_or(layout)
        } else {
            layout
        }
    }

    /// Ask the kernel to back `[ptr, ptr + size)` with huge pages (advice only: a refusal
    /// changes nothing).
    fn advise(ptr: *mut u8, size: usize) {
        if ptr.is_null() || size < LARGE || !wanted() {
            return;
        }
        #[cfg(target_os = "linux")]
        // SAFETY: the range was just allocated for us and is mapped; MADV_HUGEPAGE only
        // changes how the kernel backs it, never its contents
        unsafe {
            libc::madvise(ptr.cast(), size, libc::MADV_HUGEPAGE);
        }
    }
}

// SAFETY: every call forwards to `System` with a layout at least as aligned as asked for, and
// deallocation and reallocation use the same rule (`served`) to recover the layout allocated.
unsafe impl GlobalAlloc for HugePages {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let served = Self::served(layout);
        let ptr = System.alloc(served);
        Self::advise(ptr, served.size());
        ptr
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let served = Self::served(layout);
        let ptr = System.alloc_zeroed(served);
        Self::advise(ptr, served.size());
        ptr
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, Self::served(layout))
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let old = Self::served(layout);
        // SAFETY: the caller guarantees new_size > 0 and a valid size for this alignment
        let new = Self::served(Layout::from_size_align_unchecked(new_size, layout.align()));
        if old.align() == new.align() {
            let ptr = System.realloc(ptr, old, new.size());
            Self::advise(ptr, new.size());
            return ptr;
        }
        // crossing the large threshold changes the alignment: move by hand
        let fresh = self.alloc(Layout::from_size_align_unchecked(new_size, layout.align()));
        if !fresh.is_null() {
            std::ptr::copy_nonoverlapping(ptr, fresh, layout.size().min(new_size));
            self.dealloc(ptr, layout);
        }
        fresh
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn large_allocations_are_huge_page_aligned_and_keep_their_contents() {
        let a = HugePages;
        unsafe {
            let small = Layout::from_size_align(1000, 8).unwrap();
            let p = a.alloc(small);
            assert!(!p.is_null());
            p.write_bytes(7, 1000);
            // grow across the threshold: contents kept, now aligned to a huge page
            let q = a.realloc(p, small, LARGE + 5);
            assert_eq!(q as usize % HUGE_PAGE, 0);
            assert_eq!(std::slice::from_raw_parts(q, 1000), &[7u8; 1000][..]);
            let big = Layout::from_size_align(LARGE + 5, 8).unwrap();
            // grow while large, then shrink below the threshold again
            let r = a.realloc(q, big, 3 * LARGE);
            assert_eq!(r as usize % HUGE_PAGE, 0);
            assert_eq!(*r.add(999), 7);
            let bigger = Layout::from_size_align(3 * LARGE, 8).unwrap();
            let s = a.realloc(r, bigger, 64);
            assert_eq!(std::slice::from_raw_parts(s, 64), &[7u8; 64][..]);
            a.dealloc(s, Layout::from_size_align(64, 8).unwrap());
            let z = a.alloc_zeroed(big);
            assert_eq!(z as usize % HUGE_PAGE, 0);
            assert!(std::slice::from_raw_parts(z, LARGE + 5)
                .iter()
                .all(|&b| b == 0));
            a.dealloc(z, big);
        }
    }
}

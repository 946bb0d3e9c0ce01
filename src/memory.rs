//! Large vectors backed by transparent huge pages.
//!
//! The AST of a large program and the toolpath of a cycle-heavy one are hundreds of MB
//! written once, front to back. With 4 KiB pages the kernel takes tens of thousands of
//! faults to hand that memory over, a large share of the parse time, so both ask for huge
//! pages where the system allows it.

/// A vector with room for `capacity` items whose memory, when it is large, is backed by
/// transparent huge pages where the system allows it (Linux `madvise`). Growing it later
/// keeps the advice: glibc grows a large allocation with `mremap`, which moves the mapping
/// with its flags and copies nothing.
pub(crate) fn huge_page_vec<T>(capacity: usize) -> Vec<T> {
    let vec = Vec::with_capacity(capacity);
    #[cfg(target_os = "linux")]
    {
        const PAGE: usize = 4096;
        let start = vec.as_ptr() as usize;
        let end = start + vec.capacity() * std::mem::size_of::<T>();
        // madvise wants page-aligned addresses; the allocator's header shares the first page.
        let aligned_start = start.div_ceil(PAGE) * PAGE;
        let aligned_end = end / PAGE * PAGE;
        if aligned_end > aligned_start && aligned_end - aligned_start >= 4 << 20 {
            // SAFETY: the range lies inside the vector's own allocation, which stays alive for
            // the call; MADV_HUGEPAGE is advice about how to back the pages and changes no
            // contents. A failure (no THP support) leaves ordinary pages, which is fine.
            unsafe {
                let _ =
                    libc::madvise(aligned_start as *mut libc::c_void, aligned_end - aligned_start, libc::MADV_HUGEPAGE);
            }
        }
    }
    vec
}

//! The one mechanism every handle type uses: a handle takes one call at a time.
//!
//! A handle is a [`Guarded`] value behind the C pointer: an atomic state (idle, in use, in use
//! with a release requested) and the value. Every entry point acquires the handles it is given
//! ([`acquire`]); a second call on a handle in use, from the progress callback of the first or
//! from another thread, fails with `IGAPARAM_STATUS_BUSY` instead of racing. `*_free` of a
//! handle in use does not release it under the running call: it marks the release, the running
//! call stops at its next progress point (`IGAPARAM_STATUS_CANCELLED`) and the handle is
//! released when that call returns ([`release`]).

use std::cell::UnsafeCell;
use std::marker::PhantomData;
use std::ops::{Deref, DerefMut};
use std::sync::atomic::{AtomicU8, Ordering};

use super::ffi::{non_null, Failure};
use crate::error::{Error, ErrorKind};

const IDLE: u8 = 0;
const IN_USE: u8 = 1;
const RELEASE_PENDING: u8 = 2;

/// A handle's value and its in-use state.
pub struct Guarded<T> {
    state: AtomicU8,
    value: UnsafeCell<T>,
}

// SAFETY: the value is reached only through a `Held`, of which the state admits one at a time
// (acquired with Acquire, released with Release ordering), so it is never shared between threads.
unsafe impl<T: Send> Sync for Guarded<T> {}

impl<T> Guarded<T> {
    /// A new, idle handle value.
    pub(crate) fn new(value: T) -> Self {
        Guarded {
            state: AtomicU8::new(IDLE),
            value: UnsafeCell::new(value),
        }
    }
}

/// A C handle type: an opaque struct wrapping a [`Guarded`] value.
pub(crate) trait Handle: Sized {
    /// What the handle holds.
    type Inner: Send;
    /// What the handle is, for messages ("mesh", "domain", "spline").
    const KIND: &'static str;
    /// Wraps a guarded value.
    fn wrap(value: Guarded<Self::Inner>) -> Self;
    /// The guarded value.
    fn guarded(&self) -> &Guarded<Self::Inner>;
}

/// Makes `$name`, a tuple struct around a `Guarded<$inner>` (written out where it is declared,
/// so that the header generator sees it), a [`Handle`].
macro_rules! handle_type {
    ($name:ident, $inner:ty, $kind:literal) => {
        impl super::handle::Handle for $name {
            type Inner = $inner;
            const KIND: &'static str = $kind;
            fn wrap(value: super::handle::Guarded<$inner>) -> Self {
                $name(value)
            }
            fn guarded(&self) -> &super::handle::Guarded<$inner> {
                &self.0
            }
        }
    };
}
pub(crate) use handle_type;

/// A new heap handle holding `value`, to be released with [`release`].
pub(crate) fn into_raw<H: Handle>(value: H::Inner) -> *mut H {
    Box::into_raw(Box::new(H::wrap(Guarded::new(value))))
}

/// The exclusive use of a handle during one call; releases it (and frees a handle whose release
/// was requested meanwhile) when dropped.
pub(crate) struct Held<'a, H: Handle> {
    ptr: *mut H,
    _value: PhantomData<&'a mut H::Inner>,
}

impl<H: Handle> Held<'_, H> {
    fn guarded(&self) -> &Guarded<H::Inner> {
        // SAFETY: `ptr` is a live handle: it is freed only by this `Held`'s drop.
        unsafe { &*self.ptr }.guarded()
    }

    /// The value and a watch of the handle's release request, for progress callbacks (the
    /// watch reads only the state, never the value).
    pub(crate) fn split(&mut self) -> (&mut H::Inner, ReleaseWatch<'_>) {
        // SAFETY: `ptr` is live (as in `guarded`); the state is IN_USE (or RELEASE_PENDING) for
        // this `Held` only, so the value is ours, and the watch reads the disjoint state field.
        let guarded = unsafe { &*self.ptr }.guarded();
        (
            unsafe { &mut *guarded.value.get() },
            ReleaseWatch(&guarded.state),
        )
    }
}

/// Whether `*_free` was called on a handle in use (the running call then cancels).
#[derive(Clone, Copy)]
pub(crate) struct ReleaseWatch<'a>(&'a AtomicU8);

impl ReleaseWatch<'_> {
    /// True once the release of the handle was requested.
    pub(crate) fn requested(&self) -> bool {
        self.0.load(Ordering::Acquire) == RELEASE_PENDING
    }

    /// Says why a call cancelled when it was for a release of its handle.
    pub(crate) fn explain(&self, e: Error) -> Error {
        if e.kind == ErrorKind::Cancelled && self.requested() {
            Error::new(
                ErrorKind::Cancelled,
                "cancelled: the handle was released (its *_free was called) during the call; it \
                 is released as the call returns",
            )
        } else {
            e
        }
    }
}

impl<H: Handle> Deref for Held<'_, H> {
    type Target = H::Inner;
    fn deref(&self) -> &H::Inner {
        // SAFETY: the state is IN_USE (or RELEASE_PENDING) for this `Held` only.
        unsafe { &*self.guarded().value.get() }
    }
}

impl<H: Handle> DerefMut for Held<'_, H> {
    fn deref_mut(&mut self) -> &mut H::Inner {
        // SAFETY: as in `deref`; `&mut self` makes the borrow unique.
        unsafe { &mut *self.guarded().value.get() }
    }
}

impl<H: Handle> Drop for Held<'_, H> {
    fn drop(&mut self) {
        let released = self.guarded().state.compare_exchange(
            IN_USE,
            IDLE,
            Ordering::AcqRel,
            Ordering::Acquire,
        );
        if released.is_err() {
            // RELEASE_PENDING: `*_free` was called during the call; this call owns the release.
            // SAFETY: `ptr` came from `into_raw` and nothing else frees a pending handle.
            drop(unsafe { Box::from_raw(self.ptr) });
        }
    }
}

/// Takes handle `ptr` (argument `name`) for the current call: NULL is a NULL argument, a handle
/// in use by another call is `IGAPARAM_STATUS_BUSY`.
pub(crate) fn acquire<'a, H: Handle>(
    ptr: *const H,
    name: &'static str,
) -> std::result::Result<Held<'a, H>, Failure> {
    let handle = non_null(ptr, name)?;
    match handle
        .guarded()
        .state
        .compare_exchange(IDLE, IN_USE, Ordering::AcqRel, Ordering::Acquire)
    {
        Ok(_) => Ok(Held {
            ptr: ptr as *mut H,
            _value: PhantomData,
        }),
        Err(_) => Err(Failure::Busy(name, H::KIND)),
    }
}

/// Releases handle `ptr` (NULL: nothing). A handle in use is released when its call returns;
/// that call cancels at its next progress point. A second release of a pending one does
/// nothing.
pub(crate) fn release<H: Handle>(ptr: *mut H) {
    if ptr.is_null() {
        return;
    }
    // SAFETY: `ptr` came from `into_raw` and was not released (the caller's contract).
    let state = &unsafe { &*ptr }.guarded().state;
    loop {
        match state.compare_exchange(IDLE, IN_USE, Ordering::AcqRel, Ordering::Acquire) {
            Ok(_) => {
                // SAFETY: the handle is idle and now ours: nobody else holds it.
                drop(unsafe { Box::from_raw(ptr) });
                return;
            }
            Err(IN_USE) => {
                if state
                    .compare_exchange(IN_USE, RELEASE_PENDING, Ordering::AcqRel, Ordering::Acquire)
                    .is_ok()
                {
                    return;
                }
                // The call ended meanwhile: try again.
            }
            Err(_) => return,
        }
    }
}

//! Saving on the web page: a page has no save dialog and no files, so
//! what the user saves is given to the browser as a download (a Blob and
//! an `<a download>` click), under the name the desktop's dialog would
//! offer. The bytes are made on a worker, which has no document to click
//! in: [`SaveTo::write`] queues them and the page's thread hands them to
//! the browser ([`give_downloads`], each frame).

use std::sync::Mutex;

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

use crate::gui::app::{FileDialog as AskFile, FileQuestion};

/// Why a page greys out what opens or writes files on the computer
/// ([`super::file_button`]): it has no file dialog or folder picker, and
/// may read only what is dropped on it or fetched from its site.
pub(crate) const NO_FILES: Option<&str> = Some(
    "a web page cannot open or write files and folders on this computer: \
     drop a scene (.p3f, .nff) or a lesson (.toml) on the page, or open one by link \
     (?scene=, ?lesson=); images, the report and progress save as downloads",
);

/// Downloads made on a worker and not yet given to the browser: a name
/// and its bytes.
static QUEUED: Mutex<Vec<(String, Vec<u8>)>> = Mutex::new(Vec::new());

/// Where bytes the user saves go on the page: a download under this name.
pub(crate) struct SaveTo(String);

impl SaveTo {
    /// A download named as `question` offers (the page asks nothing:
    /// the browser saves downloads where its user said).
    pub(crate) fn ask(_dialog: &dyn AskFile, question: &FileQuestion) -> Option<Self> {
        Some(Self(
            question.name.clone().unwrap_or_else(|| "download".into()),
        ))
    }

    /// A download named `name`, asking no one.
    pub(crate) fn named(name: String) -> Self {
        Self(name)
    }

    /// Where the bytes go, as the window says it.
    pub(crate) fn describe(&self) -> String {
        format!("{} (a download)", self.0)
    }

    /// Queues `bytes` as the download, given to the browser by the page's
    /// thread on its next frame (which background work keeps coming).
    pub(crate) fn write(&self, bytes: &[u8]) -> anyhow::Result<()> {
        QUEUED
            .lock()
            .map_err(|_| anyhow::anyhow!("the download queue is broken"))?
            .push((self.0.clone(), bytes.to_vec()));
        Ok(())
    }
}

/// Gives the queued downloads to the browser; on the page's thread,
/// which may not wait: when a worker holds the queue, true (look again
/// next frame).
pub(crate) fn give_downloads() -> bool {
    let Ok(mut queued) = QUEUED.try_lock() else {
        return true;
    };
    for (name, bytes) in queued.drain(..) {
        if let Err(e) = download(&name, &bytes) {
            web_sys::console::error_1(&format!("cannot download {name}: {e:?}").into());
        }
    }
    false
}

/// The browser's download of `bytes` as `name`: a Blob's URL clicked in
/// an `<a download>`.
fn download(name: &str, bytes: &[u8]) -> Result<(), JsValue> {
    let window = web_sys::window().ok_or_else(|| JsValue::from_str("no window"))?;
    let document = window
        .document()
        .ok_or_else(|| JsValue::from_str("no document"))?;
    // A copy out of the shared memory: a Blob cannot view a
    // SharedArrayBuffer.
    let array = js_sys::Uint8Array::new_with_length(bytes.len() as u32);
    array.copy_from(bytes);
    let parts = js_sys::Array::of1(&array);
    let blob = web_sys::Blob::new_with_u8_array_sequence(&parts)?;
    let url = web_sys::Url::create_object_url_with_blob(&blob)?;
    let anchor = document
        .create_element("a")?
        .dyn_into::<web_sys::HtmlAnchorElement>()?;
    anchor.set_href(&url);
    anchor.set_download(name);
    anchor.click();
    // Freed once the browser has surely read it (some read it after the
    // click returns).
    let free = Closure::once_into_js(move || {
        let _ = web_sys::Url::revoke_object_url(&url);
    });
    window.set_timeout_with_callback_and_timeout_and_arguments_0(free.unchecked_ref(), 60_000)?;
    Ok(())
}

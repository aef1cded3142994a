//! A link's files and the scenes the page does not embed: fetched from
//! the page's own site (a URL relative to the page), their progress
//! followed as they arrive; and the page's address for Copy link.

use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;
use wasm_bindgen_futures::JsFuture;

use super::transfer::Transfer;

/// Fetches `url` (relative to the page) and gives its bytes, or why there
/// are none (a 404 said with the URL), to `done` on the page's thread;
/// `progress` follows it as it arrives, and stops it when cancelled.
pub(crate) fn fetch(
    url: &str,
    progress: Transfer,
    done: impl FnOnce(Result<Vec<u8>, String>) + 'static,
) {
    let url = url.to_string();
    wasm_bindgen_futures::spawn_local(async move {
        let bytes = fetched(&url, &progress).await.map_err(|e| {
            format!(
                "{url}: {}",
                e.as_string().unwrap_or_else(|| format!("{e:?}"))
            )
        });
        done(bytes);
    });
}

/// The bytes at `url` (relative to the page), or why there are none,
/// read chunk by chunk as they arrive: `progress` counts them against
/// the response's `Content-Length`, and its cancel stops the reading.
pub(crate) async fn fetched(url: &str, progress: &Transfer) -> Result<Vec<u8>, JsValue> {
    let window = web_sys::window().ok_or_else(|| JsValue::from_str("no window"))?;
    let response: web_sys::Response = JsFuture::from(window.fetch_with_str(url))
        .await
        .map_err(|_| JsValue::from_str("the page's site did not answer"))?
        .dyn_into()?;
    if !response.ok() {
        return Err(JsValue::from_str(&format!(
            "the page's site has no such file ({} {})",
            response.status(),
            response.status_text()
        )));
    }
    let total = response.headers().get("content-length").ok().flatten();
    let total = total.and_then(|t| t.parse::<u64>().ok());
    progress.set_total(total);
    let Some(body) = response.body() else {
        return Ok(Vec::new());
    };
    let reader: web_sys::ReadableStreamDefaultReader = body.get_reader().dyn_into()?;
    // The announced size, within reason: a header is no promise.
    let mut bytes = Vec::with_capacity(total.unwrap_or(0).min(1 << 26) as usize);
    loop {
        if progress.is_cancelled() {
            // Dropped: the reader's promise says nothing to anyone.
            let _ = reader.cancel();
            return Err(JsValue::from_str("cancelled: another scene was picked"));
        }
        let chunk: web_sys::ReadableStreamReadResult =
            JsFuture::from(reader.read()).await?.unchecked_into();
        if chunk.get_done() == Some(true) {
            return Ok(bytes);
        }
        let chunk = js_sys::Uint8Array::new(&chunk.get_value());
        bytes.extend(chunk.to_vec());
        progress.add(u64::from(chunk.length()));
    }
}

/// The page's address without its query, for Copy link.
pub(crate) fn page_address() -> String {
    web_sys::window()
        .map(|w| w.location())
        .and_then(|l| Some(format!("{}{}", l.origin().ok()?, l.pathname().ok()?)))
        .unwrap_or_default()
}

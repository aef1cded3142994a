#!/usr/bin/env bash
# Builds the workbench as a web page into web/dist/: index.html, the .wasm
# and its JavaScript glue under content-hashed names (a new version is
# never mixed with a cached old one), wasm-bindgen's worker helper, and
# scenes/ (the scenes the page does not embed, fetched by name).
# Installs what it needs if missing, idempotently: Debian's web toolchain
# (rustc-web, rust-web-src, lld-16, rust-web-clippy), the link through
# which cargo's build-std finds the standard library's sources, and
# wasm-bindgen-cli at exactly Cargo.lock's wasm-bindgen version, in the
# web target folder. docs/guide/web.md says how it works.
#
#   scripts/build-web.sh           build web/dist/
#   scripts/build-web.sh --check   check the tracer and the app for the web
#                                  (clippy, -D warnings, with web/clippy.toml:
#                                  no std clock that panics on the web)
#
# WEB_TARGET_DIR (default target-web/) holds the web build: never the
# native target/, as the two compilers share no build output.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
target_dir=${WEB_TARGET_DIR:-$root/target-web}
dist=$root/web/dist
mode=${1:-build}

install_toolchain() {
    local packages=(rustc-web rust-web-src lld-16 rust-web-clippy) missing=()
    for p in "${packages[@]}"; do
        dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
    done
    if [ ${#missing[@]} -gt 0 ]; then
        local sudo=""
        [ "$(id -u)" = 0 ] || sudo="sudo"
        echo "== installing ${missing[*]}"
        $sudo apt-get update -qq
        DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
    fi
    # build-std reads the sources at the sysroot's lib/rustlib/src/rust.
    local link source
    link="$(/usr/bin/rustc --print sysroot)/lib/rustlib/src/rust"
    if [ ! -e "$link/library/std/Cargo.toml" ]; then
        source=$(dpkg -L rust-web-src | grep -m1 -E '^/usr/src/rustc-[0-9.]+$')
        echo "== linking $link -> $source"
        local sudo=""
        [ "$(id -u)" = 0 ] || sudo="sudo"
        $sudo mkdir -p "$(dirname "$link")"
        $sudo ln -sfn "$source" "$link"
    fi
}

# wasm-bindgen-cli must be exactly the library's version.
install_bindgen() {
    local version
    version=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/[^0-9.]/, ""); print; exit }' "$root/Cargo.lock")
    bindgen=$target_dir/tools/bin/wasm-bindgen
    if [ ! -x "$bindgen" ] || [ "$("$bindgen" --version)" != "wasm-bindgen $version" ]; then
        echo "== installing wasm-bindgen-cli $version"
        cargo install --quiet wasm-bindgen-cli --version "=$version" --root "$target_dir/tools"
    fi
}

# The web compiler, std rebuilt with shared memory (threads on Web
# Workers), linked by lld.
export RUSTC=/usr/bin/rustc RUSTC_BOOTSTRAP=1
export CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_LINKER=wasm-ld-16
export CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUSTFLAGS="-C target-feature=+atomics,+bulk-memory,+mutable-globals,+simd128"
web=(--target wasm32-unknown-unknown -Zbuild-std=std,panic_abort --target-dir "$target_dir")

install_toolchain
cd "$root"

if [ "$mode" = --check ]; then
    # Debian's clippy, the one that matches the web compiler.
    CLIPPY_CONF_DIR=$root/web /usr/bin/cargo-clippy clippy -p tracer -p workbench --lib "${web[@]}" -- -D warnings
    exit 0
fi

install_bindgen
# Shared memory at the link (wasm-ld does not choose it from +atomics):
# given to the final crate alone, so changing it rebuilds no dependency.
shared_memory=(--shared-memory --max-memory=4294967296 --import-memory
    --export=__wasm_init_tls --export=__tls_size --export=__tls_align --export=__tls_base)
cargo rustc -p workbench --lib --crate-type cdylib --profile web "${web[@]}" -- \
    "${shared_memory[@]/#/-Clink-arg=}"

staging=$target_dir/web-dist
rm -rf "$staging"
"$bindgen" --target web --no-typescript --out-dir "$staging" --out-name workbench \
    "$target_dir/wasm32-unknown-unknown/web/workbench.wasm"
# Content-hashed names; the worker helper (snippets/) imports the glue by
# the URL the glue itself was loaded from, so it follows the rename.
hash_of() { sha256sum "$1" | cut -c1-12; }
wasm=workbench-$(hash_of "$staging/workbench_bg.wasm").wasm
mv "$staging/workbench_bg.wasm" "$staging/$wasm"
js=workbench-$(cat "$staging/workbench.js" <(echo "$wasm") | sha256sum | cut -c1-12).js
mv "$staging/workbench.js" "$staging/$js"
sed -e "s/@JS@/$js/g" -e "s/@WASM@/$wasm/g" "$root/web/index.html" >"$staging/index.html"
# The scenes the page does not embed, fetched by name (?bench=mount_high).
cp -r "$root/scenes" "$staging/scenes"
rm -rf "$dist"
mkdir -p "$(dirname "$dist")"
mv "$staging" "$dist"
echo "web/dist: $js, $wasm ($(stat -c %s "$dist/$wasm") bytes, $(gzip -9c "$dist/$wasm" | wc -c) gzipped)"

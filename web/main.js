// Bootstrap: load the wasm module (which mounts the app) and show a clear
// message if that fails. Everything else lives in Rust.
import init from "./pkg/labweb.js";

const fatal = (message) => {
  const box = document.getElementById("fatal");
  box.querySelector(".fatal-text").textContent = message;
  box.hidden = false;
  const loading = document.querySelector("#app .loading");
  if (loading) loading.textContent = "The simulation engine could not start.";
};

document.querySelector("#notice .notice-close").addEventListener("click", () => {
  document.getElementById("notice").hidden = true;
});

if (typeof WebAssembly !== "object") {
  fatal("This browser does not support WebAssembly; please use a current version of Firefox, Chrome, Edge or Safari.");
} else {
  init().catch((error) => {
    fatal(`The simulation engine failed to load (${error}). If you opened the file directly, serve the folder over HTTP instead.`);
  });
}

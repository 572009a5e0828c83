// Build the editor into dist/ with relative asset paths, so the gateway can serve it from any prefix.
import { defineConfig } from "vite";

export default defineConfig({
  base: "./",
  build: {
    outDir: "dist",
    emptyOutDir: true,
    chunkSizeWarningLimit: 1200,
  },
  server: {
    // `npm run dev` talks to a gateway started with: wana serve --allow-origin http://localhost:5173
    proxy: { "/api": { target: "http://127.0.0.1:8765", ws: true } },
  },
});

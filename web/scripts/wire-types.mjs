// Writes src/wire.ts, the browser's types of what the console sends, from schema/wire.json (the one place they
// are written). Run by `npm run build`; the file it writes is not to be edited.
import fs from "node:fs";
import path from "node:path";
import { fileURLToPath } from "node:url";

const web = path.dirname(path.dirname(fileURLToPath(import.meta.url)));
const schema = JSON.parse(fs.readFileSync(path.join(web, "schema/wire.json"), "utf8"));
const refName = (ref) => ref.replace("#/$defs/", "");

function typeOf(node, indent) {
  if (node.$ref) return refName(node.$ref);
  if (node.const !== undefined) return JSON.stringify(node.const);
  if (node.enum) return node.enum.map((v) => JSON.stringify(v)).join(" | ");
  if (node.oneOf) return node.oneOf.map((n) => typeOf(n, indent)).join(" | ");
  const types = Array.isArray(node.type) ? node.type : [node.type];
  return types.map((t) => {
    switch (t) {
      case "string": return "string";
      case "number": case "integer": return "number";
      case "boolean": return "boolean";
      case "null": return "null";
      case "array": return `${wrap(typeOf(node.items, indent))}[]`;
      case "object":
        if (node.properties) return `{\n${members(node, indent + "  ")}${indent}}`;
        if (node.additionalProperties) return `Record<string, ${typeOf(node.additionalProperties, indent)}>`;
        return "Record<string, unknown>";
      default: throw new Error(`schema/wire.json: a type the generator does not know: ${JSON.stringify(node)}`);
    }
  }).join(" | ");
}
const wrap = (t) => (/[ |]/.test(t) && !t.startsWith("{") ? `(${t})` : t);

function members(node, indent) {
  const required = new Set(node.required ?? []);
  return Object.entries(node.properties ?? {}).map(([name, p]) =>
    `${p.$comment ? `${indent}/** ${p.$comment} */\n` : ""}${indent}${name}${required.has(name) ? "" : "?"}: ${typeOf(p, indent)};\n`).join("");
}

let out = "// Generated from schema/wire.json by scripts/wire-types.mjs (npm run build): edit the schema, not this file.\n";
for (const [name, def] of Object.entries(schema.$defs)) {
  out += "\n";
  if (def.$comment) out += `/** ${def.$comment} */\n`;
  if (def.type === "object" && def.properties) {
    const bases = (def.allOf ?? []).map((b) => refName(b.$ref));
    out += `export interface ${name}${bases.length ? ` extends ${bases.join(", ")}` : ""} {\n${members(def, "  ")}}\n`;
  } else {
    out += `export type ${name} = ${typeOf(def, "")};\n`;
  }
}
fs.writeFileSync(path.join(web, "src/wire.ts"), out);

// Checks what the console sent against schema/wire.json, the schema the browser's types are generated from:
// a field the console adds, drops or sends as another type is named with its path.
import fs from "node:fs";
import path from "node:path";
import { fileURLToPath } from "node:url";

const schema = JSON.parse(fs.readFileSync(path.join(path.dirname(fileURLToPath(import.meta.url)), "../schema/wire.json"), "utf8"));
const resolve = (node) => (node.$ref ? schema.$defs[node.$ref.replace("#/$defs/", "")] : node);

function kindOf(v) {
  if (v === null) return "null";
  if (Array.isArray(v)) return "array";
  if (typeof v === "number") return Number.isInteger(v) ? "integer" : "number";
  return typeof v;
}

function check(value, node, at, errors) {
  node = resolve(node);
  for (const base of node.allOf ?? []) check(value, { ...resolve(base), additionalProperties: true }, at, errors);
  if (node.const !== undefined && value !== node.const) errors.push(`${at}: ${JSON.stringify(value)}, not ${JSON.stringify(node.const)}`);
  if (node.enum && !node.enum.includes(value)) errors.push(`${at}: ${JSON.stringify(value)}, not one of ${node.enum.join(", ")}`);
  if (node.type) {
    const types = Array.isArray(node.type) ? node.type : [node.type];
    const kind = kindOf(value);
    if (!types.includes(kind) && !(kind === "integer" && types.includes("number"))) {
      errors.push(`${at}: a ${kind}, not ${types.join(" or ")}`);
      return;
    }
  }
  if (Array.isArray(value) && node.items) value.forEach((v, k) => check(v, node.items, `${at}[${k}]`, errors));
  if (kindOf(value) !== "object") return;
  for (const name of node.required ?? []) if (!(name in value)) errors.push(`${at}: no '${name}'`);
  const allowed = new Set([...Object.keys(node.properties ?? {}),
    ...(node.allOf ?? []).flatMap((b) => Object.keys(resolve(b).properties ?? {}))]);
  for (const [name, v] of Object.entries(value)) {
    if (node.properties?.[name]) check(v, node.properties[name], `${at}.${name}`, errors);
    else if (typeof node.additionalProperties === "object") check(v, node.additionalProperties, `${at}.${name}`, errors);
    else if (node.additionalProperties === false && !allowed.has(name)) errors.push(`${at}: '${name}' is not in the schema`);
  }
}

/** What is wrong with `value` as the schema's `name` ([] when nothing). */
export function wireErrors(value, name) {
  if (!schema.$defs[name]) throw new Error(`schema/wire.json has no ${name}`);
  const errors = [];
  check(value, schema.$defs[name], name, errors);
  return errors;
}

/** The schema's message for a live socket message by its type (the LiveMessage union's). */
export const MESSAGE_OF_TYPE = Object.fromEntries(schema.$defs.LiveMessage.oneOf.map((r) =>
  [resolve(r).properties.type.const, r.$ref.replace("#/$defs/", "")]));

-- The same through a linked folder: mods/ → a folder outside holding a module.
-- file: outside/secret.lua
-- link: mods -> outside
-- exit: 1
-- expect: require: module 'mods.secret' (mods/secret.lua) is a link to a file outside the scene's folder and the module folders: refused
-- reject: outside"
function PopulateWorld(world) print(require("mods.secret")) end

-- require followed a symbolic link in the mod's folder out of it (a scene read /etc/os-release and
-- printed it in its JSON). The real path of a module must lie inside the allowed folders.
-- link: evil.lua -> /etc/os-release
-- exit: 1
-- expect: require_link.lua:7: require: module 'evil' (evil.lua) is a link to a file outside the scene's folder and the module folders: refused
-- reject: PRETTY_NAME
function PopulateWorld(world) print(require("evil")) end

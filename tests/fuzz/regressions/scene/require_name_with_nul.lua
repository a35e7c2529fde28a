-- require("check\0evil") was cut at the NUL and loaded "check".
function PopulateWorld(world) require("check\0evil") end

# The scene sets of the experiments, spelled once (sourced by scripts/results.sh and
# scripts/tune_table.sh):
#   default: scenarios/teapots.json (the README's default run)
#   paper:   scenarios/paper/{teapots,city,library,plant}.json (the paper's scenes)
#   general: scenarios/general/*.json (the generalisation set)
#   levels:  scenarios/levels/*.json (game levels: courtyards, interior, street canyon)
#   all:     default, paper, general and levels, in that order
# scene_sets_of NAME CALLER: the sets NAME stands for, one a line; a name that is no set is one
# line on stderr naming CALLER and the choices, and exit status 2.
# scenes_of SET: the scenario files of SET, one a line, in a fixed order.
scene_set_names=(default paper general levels)

scene_sets_of() {
  case "$1" in
    default | paper | general | levels) echo "$1" ;;
    all) printf '%s\n' "${scene_set_names[@]}" ;;
    *)
      local IFS=,
      echo "$2: unknown set '$1'; expected one of ${scene_set_names[*]},all" >&2
      return 2
      ;;
  esac
}

scenes_of() {
  case "$1" in
    default) echo scenarios/teapots.json ;;
    paper) printf '%s\n' scenarios/paper/teapots.json scenarios/paper/city.json \
      scenarios/paper/library.json scenarios/paper/plant.json ;;
    general) printf '%s\n' scenarios/general/*.json ;;
    levels) printf '%s\n' scenarios/levels/*.json ;;
  esac
}

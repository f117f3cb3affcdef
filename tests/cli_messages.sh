# What the program tells a user: messages in user terms.  Every message
# a scene can trigger names what and where without the library's
# function names (sc_...), without text cut mid-sentence ("at )") and
# without the valid values given twice; help texts state the model's laws
# with their parameters.
. "$(dirname "$0")/cli_common.sh"

# The friction law of `slipcont models` shows gamma, the parameter that
# scales the velocity weakening.
run_sc models
expect_rc "models" 0
line=$(printf '%s\n' "$OUT" | grep '^  friction ')
case $line in
*"T_i / (1 + gamma |U_i - V_s|)"*) pass "models: the friction law shows gamma" ;;
*) fail "models: the friction law '$line' lacks gamma" ;;
esac

finish

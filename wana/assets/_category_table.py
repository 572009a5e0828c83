"""Raw category table for ``wana.assets.vocabulary`` (data only).

Each row: ``name | parent | synonyms (comma separated) | room types | knobs | mount``.

- parent: the direct hypernym (another category or an abstract class in ``ABSTRACT_PARENTS``).
- knobs: letters for the attribute knobs that apply: S size, T style, C colour, M material, X state.
- mount: ``floor`` (stands on the floor), ``surface`` (rests on a support surface such as a table),
  ``wall`` (hangs on or sits in a wall).
"""

from __future__ import annotations

# Abstract hypernyms (not catalog categories themselves) -> their parent ("" = top level).
ABSTRACT_PARENTS: dict[str, str] = {
    "furniture": "",
    "seat": "furniture",
    "storage": "furniture",
    "lighting": "furniture",
    "electronics": "",
    "computer_peripheral": "electronics",
    "display": "electronics",
    "office_equipment": "electronics",
    "audio_equipment": "electronics",
    "appliance": "electronics",
    "kitchen_appliance": "appliance",
    "instrument": "",
    "keyboard_instrument": "instrument",
    "string_instrument": "instrument",
    "wind_instrument": "instrument",
    "percussion": "instrument",
    "music_equipment": "instrument",
    "board": "teaching_equipment",
    "teaching_equipment": "",
    "stationery": "",
    "bag": "container",
    "container": "",
    "artwork": "decoration",
    "decoration": "",
    "textile": "decoration",
    "architecture": "",
    "tableware": "kitchenware",
    "drinkware": "kitchenware",
    "cookware": "kitchenware",
    "kitchenware": "",
    "sink": "bathroom_fixture",
    "bathroom_fixture": "fixture",
    "fixture": "",
    "toiletry": "",
    "sports_equipment": "",
    "boxing_equipment": "sports_equipment",
    "gym_machine": "sports_equipment",
    "weights": "sports_equipment",
    "tool": "",
    "hand_tool": "tool",
    "power_tool": "tool",
    "workshop_equipment": "tool",
    "building_material": "",
    "fastener": "building_material",
    "toy": "",
    "vehicle": "",
    "safety_equipment": "",
    "food": "",
    "medicine": "",
}

# fmt: off
CATEGORY_ROWS = """
table | furniture | plain table, wooden table, tables | dining_room kitchen living_room cafe office classroom | STCMX | floor
chair | seat | side chair, wooden chair, plain chair | living_room dining_room office classroom kitchen bedroom meeting_room cafe library | STCM | floor
office_chair | chair | desk chair, swivel chair, computer chair, task chair, executive chair, modernchair | office home_office meeting_room music_studio | STCM | floor
armchair | chair | arm chair, easy chair, lounge chair, club chair, recliner, wing chair | living_room bedroom library lobby | STCM | floor
dining_chair | chair | kitchen chair, dinner chair | dining_room kitchen cafe | STCM | floor
folding_chair | chair | camp chair, fold up chair, foldable chair | classroom workshop garage meeting_room | SCM | floor
rocking_chair | chair | rocker | living_room kids_room bedroom | STCM | floor
school_chair | chair | student chair, classroom chair, pupil chair | classroom | SCM | floor
stool | seat | step stool, wooden stool, tabouret | workshop kitchen music_studio garage classroom | STCM | floor
bar_stool | stool | counter stool, high stool, barstool | kitchen cafe | STCM | floor
piano_bench | bench | piano stool, piano seat | music_studio living_room | SCM | floor
bench | seat | park bench, wooden bench, long seat, pew | gym gallery lobby bathroom | STCM | floor
sofa | seat | couch, settee, divan, sofa bed, davenport, chesterfield, sectional | living_room lobby office home_office | STCMX | floor
loveseat | sofa | love seat, two seater, small sofa | living_room bedroom lobby | STCM | floor
ottoman | seat | footstool, pouf, pouffe, footrest, hassock | living_room bedroom | SCM | floor
bean_bag | seat | beanbag, bean bag chair, beanbag chair | kids_room living_room | SC | floor
bed | furniture | double bed, single bed, queen bed, king bed, twin bed, bedstead | bedroom kids_room | STCMX | floor
bunk_bed | bed | bunk, bunkbed, bunk beds | kids_room | SCM | floor
crib | bed | cot, baby bed, cradle | kids_room bedroom | SCM | floor
desk | table | writing desk, computer desk, office desk, work desk, secretary desk | office home_office bedroom kids_room library | STCMX | floor
standing_desk | desk | stand up desk, sit stand desk, standup desk, height adjustable desk | office home_office | SCMX | floor
teacher_desk | desk | teachers desk, teacher's desk, instructor desk | classroom | STCMX | floor
student_desk | desk | school desk, pupil desk, classroom desk | classroom | SCMX | floor
dining_table | table | kitchen table, dinner table, dining room table, breakfast table | dining_room kitchen | STCMX | floor
coffee_table | table | cocktail table, tea table, center table, centre table, low table | living_room lobby office | STCMX | floor
side_table | table | end table, accent table, occasional table, small table | living_room bedroom lobby library | STCM | floor
nightstand | table | night stand, bedside table, night table, bedside cabinet | bedroom kids_room | STCMX | floor
conference_table | table | meeting table, boardroom table, board table | meeting_room office | STCMX | floor
workbench | table | work bench, work table, workshop table, carpenter bench, carpentry bench | workshop garage | STCMX | floor
kitchen_island | table | island, kitchen island counter, breakfast bar | kitchen | STCMX | floor
cafe_table | table | bistro table, round table, cafe table, coffee shop table | cafe kitchen | STCM | floor
kitchen_counter | table | countertop, counter, worktop, kitchen worktop | kitchen cafe | STCMX | floor
dressing_table | table | vanity, vanity table, makeup table, dressing desk | bedroom | STCMX | floor
lectern | furniture | podium, pulpit, speaker stand, speakers desk | classroom meeting_room | STCM | floor
bookshelf | storage | bookcase, book shelf, shelves, book case, shelving, book rack | library office living_room classroom home_office kids_room | STCMX | floor
shelf | storage | shelving unit, storage rack, rack, metal shelf, open shelf | workshop garage kitchen bathroom music_studio | STCMX | floor
wardrobe | storage | closet, armoire, clothes cabinet, wardrobe closet | bedroom kids_room | STCM | floor
cabinet | storage | cupboard, sideboard, credenza, buffet, storage cabinet | living_room dining_room office kitchen meeting_room | STCM | floor
filing_cabinet | cabinet | file cabinet, file drawer, filing drawers, file cupboard | office home_office | SCM | floor
dresser | cabinet | chest of drawers, drawers, commode chest, tallboy | bedroom kids_room | STCM | floor
kitchen_cabinet | cabinet | base cabinet, kitchen cupboard | kitchen | STCM | floor
tv_stand | cabinet | tv cabinet, media console, entertainment center, tv unit, tv table | living_room bedroom | STCM | floor
locker | storage | lockers, locker cabinet, gym locker | gym classroom | SCM | floor
tool_cabinet | cabinet | tool chest, tool cart, tool trolley | workshop garage | SCM | floor
chest | storage | trunk, toy chest, toy box, blanket chest, footlocker, treasure chest | bedroom kids_room | STCM | floor
shoe_rack | storage | shoe shelf, shoe cabinet, shoe stand | lobby bedroom | SCM | floor
coat_rack | storage | coat stand, hat stand, hall tree, coat hanger, hat rack | lobby office cafe | STCM | floor
display_case | storage | vitrine, showcase, display cabinet, glass case, glass cabinet | gallery lobby | STCM | floor
floor_lamp | lamp | standing lamp, standard lamp, torchiere, floorlamp | living_room bedroom office library lobby | STCM | floor
desk_lamp | lamp | table lamp, reading lamp, task lamp, bedside lamp, study lamp | office bedroom home_office library kids_room | STCM | surface
lamp | lighting | light, lamp light, lampshade, lantern | living_room bedroom office library | STCM | surface
computer | electronics | desktop computer, pc, desktop, computer tower, tower pc, workstation, personal computer | office home_office classroom library | SCT | surface
laptop | computer | notebook computer, laptop computer, macbook, notebook pc, portable computer | office home_office bedroom cafe classroom meeting_room library | SCT | surface
tablet | computer | ipad, tablet computer, e reader, kindle | office bedroom living_room cafe | SC | surface
monitor | display | computer monitor, screen, computer screen, display, lcd, flat panel | office home_office music_studio | SCT | surface
television | display | tv, telly, television set, tv set, flat screen, flatscreen | living_room bedroom lobby | SCT | surface
keyboard | computer_peripheral | computer keyboard, typing keyboard, keypad | office home_office music_studio | SCT | surface
mouse | computer_peripheral | computer mouse, mouse pad | office home_office | SC | surface
printer | office_equipment | laser printer, inkjet printer, copier, photocopier, copy machine, scanner | office home_office library | SCT | surface
projector | office_equipment | beamer, video projector, overhead projector | classroom meeting_room | SCT | surface
phone | electronics | telephone, mobile, mobile phone, cellphone, cell phone, smartphone, smart phone, iphone, handset, desk phone | office living_room bedroom home_office lobby | SCT | surface
speaker | audio_equipment | loudspeaker, speakers, studio monitor, speaker box, boombox, subwoofer | music_studio living_room gym | SCTM | floor
microphone | audio_equipment | mic, mike, microphone stand, mic stand, vocal mic | music_studio classroom meeting_room | SCT | floor
recorder | audio_equipment | tape recorder, voice recorder, audio recorder, dictaphone, cassette recorder, recording device, cassette player | music_studio office classroom | SCT | surface
headphones | audio_equipment | headphone, headset, earphones, ear phones, cans | music_studio office home_office | SCT | surface
amplifier | audio_equipment | amp, guitar amp, guitar amplifier, bass amp | music_studio | SCT | floor
mixing_console | audio_equipment | mixer, mixing desk, soundboard, sound board, audio mixer, mixing board | music_studio | SC | surface
radio | audio_equipment | radio set, stereo, transistor radio, hi fi | kitchen living_room workshop | SCTM | surface
camera | electronics | photo camera, video camera, camcorder, dslr, webcam | gallery living_room | SC | surface
game_console | electronics | console, video game console, playstation, xbox, gaming console | living_room kids_room | SC | surface
clock | decoration | wall clock, timepiece, clock face | classroom office kitchen living_room meeting_room | STCM | wall
fan | appliance | electric fan, desk fan, standing fan, floor fan, ventilator | office bedroom gym | SCT | floor
water_cooler | appliance | water dispenser, drinking fountain, water fountain, dispenser, cooler | office lobby gym | SC | floor
radiator | appliance | heater, space heater, heating, heating radiator | living_room bedroom office bathroom | SC | floor
piano | keyboard_instrument | upright piano, pianoforte, acoustic piano | music_studio living_room classroom | STCM | floor
grand_piano | piano | grand, baby grand, concert grand, concert piano | music_studio lobby | STCM | floor
synthesizer | keyboard_instrument | synth, electronic keyboard, digital piano, electric piano, keyboard instrument, keytar | music_studio | SCT | floor
guitar | string_instrument | acoustic guitar, classical guitar, spanish guitar, folk guitar | music_studio bedroom living_room | SCTM | floor
electric_guitar | guitar | e guitar, electrical guitar, lead guitar | music_studio | SCT | floor
bass_guitar | guitar | bass, electric bass, bass guitar | music_studio | SCT | floor
violin | string_instrument | fiddle, viola | music_studio classroom | SCTM | surface
cello | string_instrument | violoncello, double bass, contrabass, upright bass | music_studio | SCTM | floor
harp | string_instrument | concert harp, lyre | music_studio | SCM | floor
drum_kit | percussion | drums, drum set, drumkit, drum, drumset, drum kit, drum kits, drum kit set | music_studio | SCT | floor
trumpet | wind_instrument | horn, cornet, bugle, trombone | music_studio | SCM | surface
saxophone | wind_instrument | sax, alto sax, tenor sax, clarinet | music_studio | SCM | surface
flute | wind_instrument | piccolo, recorder flute, fife | music_studio classroom | SCM | surface
music_stand | music_equipment | sheet music stand, note stand, score stand | music_studio classroom | SCM | floor
blackboard | board | chalkboard, black board, chalk board, greenboard | classroom | SCT | wall
whiteboard | board | white board, dry erase board, marker board, wall board | classroom meeting_room office | SCT | wall
projector_screen | board | projection screen, pull down screen, movie screen | classroom meeting_room | SC | wall
flip_chart | board | flipchart, easel pad, flip board, flip chart stand | meeting_room office classroom | SC | floor
globe | teaching_equipment | world globe, terrestrial globe, earth globe | classroom library home_office | SCT | surface
book | stationery | books, novel, textbook, paperback, hardcover, magazine, encyclopedia, dictionary, album, photo album, comic book, storybook | library classroom living_room bedroom office | SCTX | surface
notebook | stationery | exercise book, notepad, jotter, copybook, note book, diary, journal | classroom office home_office | SCX | surface
paper | stationery | papers, document, documents, sheet of paper, stack of paper, report, letter, file | office home_office classroom meeting_room | SX | surface
pen | stationery | pencil, ballpoint, marker, biro, ballpoint pen, crayon, chalk | office classroom home_office | SC | surface
stapler | stationery | staple gun, hole punch | office home_office | SC | surface
backpack | bag | school bag, schoolbag, rucksack, knapsack, bookbag | classroom kids_room bedroom | SCM | floor
handbag | bag | purse, tote, tote bag, shoulder bag, shopping bag, bag | office bedroom lobby | SCM | surface
briefcase | bag | attache case, portfolio case, laptop bag | office home_office | SCM | floor
suitcase | bag | luggage, trolley case, travel bag, valise | bedroom lobby | SCM | floor
trash_can | container | trash bin, garbage can, bin, waste basket, wastebasket, dustbin, rubbish bin, garbage bin, trashcan | office kitchen bathroom classroom workshop | SCM | floor
box | container | cardboard box, carton, crate, package, parcel, storage box | garage workshop bedroom | SCMX | floor
basket | container | laundry basket, hamper, wicker basket, picnic basket | bathroom bedroom kitchen | SCM | floor
painting | artwork | picture, canvas, oil painting, artwork, art, portrait, landscape, frame, picture frame | gallery living_room bedroom office lobby dining_room | STCM | wall
poster | artwork | print, placard, wall poster, map, wall map, chart | classroom kids_room bedroom gym music_studio | SC | wall
photo_frame | artwork | photo, photograph, photo frame, family photo | living_room bedroom office | SCM | surface
sculpture | artwork | statue, figurine, carving, bust, statuette, art piece, installation | gallery lobby | STCM | floor
pedestal | furniture | plinth, display stand, column, pillar stand | gallery lobby | SCM | floor
easel | music_equipment | painting easel, art easel, drawing stand | gallery classroom | SCM | floor
mirror | decoration | looking glass, wall mirror, vanity mirror | bathroom bedroom gym lobby | STCM | wall
plant | decoration | potted plant, houseplant, house plant, flower, flowers, fern, cactus, ficus, palm, bonsai, tree, flowerpot, flower pot | living_room office lobby bedroom kitchen gallery cafe meeting_room | SCX | floor
vase | decoration | urn, flower vase, jar, amphora | living_room dining_room lobby gallery | STCM | surface
curtain | textile | curtains, drape, drapes, blind, blinds, shade, window curtain | living_room bedroom | SCM | wall
candle | decoration | candles, candlestick, candle holder, tealight | dining_room living_room bathroom | SC | surface
cushion | textile | pillow, throw pillow, pillows, cushions | living_room bedroom | SCX | surface
fireplace | architecture | hearth, chimney, fire place, wood stove | living_room library | STM | floor
window | architecture | windows, window pane, casement, windowpane | office living_room bedroom classroom kitchen meeting_room | STC | wall
door | architecture | doorway, entrance, front door, exit, entry door, elevator, elevator door, elevators, lift door | office living_room bedroom classroom kitchen bathroom | STCM | wall
teddy_bear | toy | teddy, stuffed animal, plush toy, stuffed toy, soft toy, plushie | kids_room bedroom | SC | surface
ball | toy | football, soccer ball, basketball, beach ball, volleyball | kids_room gym garage | SC | floor
refrigerator | kitchen_appliance | fridge, freezer, icebox, refrigerator freezer, refridgerator | kitchen | STC | floor
stove | kitchen_appliance | cooker, range, cooktop, hob, gas stove, oven, electric stove | kitchen | STC | floor
microwave | kitchen_appliance | microwave oven, micro wave | kitchen office | STC | surface
dishwasher | kitchen_appliance | dish washer, dish washing machine | kitchen | SC | floor
kitchen_sink | sink | sink, kitchen basin, sink unit | kitchen | STC | floor
toaster | kitchen_appliance | toaster oven, sandwich maker | kitchen | SC | surface
coffee_maker | kitchen_appliance | coffee machine, espresso machine, coffeemaker, percolator, coffee pot | kitchen cafe office | SCT | surface
kettle | kitchen_appliance | electric kettle, water kettle, tea kettle, watering can | kitchen office | SCT | surface
teapot | tableware | tea pot, tea set | kitchen dining_room cafe living_room | STCM | surface
jug | tableware | pitcher, water jug, milk jug, carafe, decanter, jugs, pitchers | kitchen dining_room cafe | SCT | surface
cup | drinkware | teacup, tea cup, coffee cup, cups, paper cup, coffee, tea, espresso, cappuccino, latte, cocoa | kitchen dining_room cafe office | SCTM | surface
mug | drinkware | coffee mug, beer mug, tankard, travel mug | kitchen office cafe | SCT | surface
glass | drinkware | drinking glass, tumbler, wine glass, wineglass, goblet, water glass, milk, juice, orange juice, wine, lemonade, smoothie | kitchen dining_room cafe | SCT | surface
bottle | drinkware | water bottle, wine bottle, flask, beer bottle, plastic bottle, water | kitchen dining_room gym office | SCTM | surface
soda_can | drinkware | can, soda, coke, cola, soft drink, drink can, beer can, tin can, soda pop | kitchen living_room office | SC | surface
plate | tableware | dish, dinner plate, saucer, platter, tray, serving tray, baking tray, tea tray, dinner, lunch, meal, food, sandwich, toast, pizza | kitchen dining_room cafe | SCM | surface
bowl | tableware | salad bowl, soup bowl, fruit bowl, cereal bowl, soup, cereal, salad, porridge, noodles, popcorn, popcorn bowl, crisps, chips, snacks, fruit | kitchen dining_room | SCM | surface
pan | cookware | frying pan, skillet, wok, saucepan, fry pan | kitchen | SCM | surface
pot | cookware | cooking pot, stockpot, casserole, stew pot | kitchen | SCM | surface
knife | cookware | kitchen knife, chef knife, chefs knife, blade, bread knife | kitchen | SM | surface
cutting_board | cookware | chopping board, bread board, carving board | kitchen | SM | surface
toilet | bathroom_fixture | wc, lavatory, loo, water closet, commode, toilet bowl | bathroom | STC | floor
bathtub | bathroom_fixture | bath, tub, bath tub, jacuzzi, hot tub | bathroom | STC | floor
shower | bathroom_fixture | shower cabin, shower stall, shower cubicle, shower booth | bathroom | STC | floor
bathroom_sink | sink | washbasin, wash basin, basin, lavatory sink, vanity sink, hand basin, washstand | bathroom | STC | floor
towel_rack | bathroom_fixture | towel rail, towel holder, towel bar, towel stand | bathroom | SCM | floor
towel | textile | bath towel, hand towel, towels, blanket, blankets, quilt, duvet, bedspread, shirt, shirts, t-shirt, clothes, clothing, garment, sweater, tea towel, rag, cloth | bathroom gym | SCX | surface
washing_machine | appliance | washer, laundry machine, tumble dryer, dryer, washer dryer | bathroom kitchen | SC | floor
boiler | appliance | water heater, hot water tank, hot water cylinder, furnace, heating boiler, combi boiler | kitchen bathroom garage workshop | SC | floor
toothbrush | toiletry | tooth brush, toothpaste | bathroom | SC | surface
soap | toiletry | soap bar, soap dispenser, bar of soap, shampoo | bathroom kitchen | SC | surface
boxing_bag | boxing_equipment | punching bag, punch bag, heavy bag, punchbag, speed bag, kick bag, sandbag, boxingbag | gym | SCM | floor
boxing_ring | boxing_equipment | ring, boxing arena, fighting ring, wrestling ring | gym | SC | floor
boxing_gloves | boxing_equipment | gloves, boxing glove, boxing mitts | gym | SC | surface
treadmill | gym_machine | running machine, running belt, treadmill machine, walking machine | gym | SCT | floor
exercise_bike | gym_machine | stationary bike, spin bike, spinning bike, exercise bicycle, home trainer | gym | SCT | floor
rowing_machine | gym_machine | rower, ergometer, erg, rowing ergometer | gym | SCT | floor
weight_bench | gym_machine | workout bench, bench press, gym bench, press bench, training bench | gym | SCT | floor
dumbbell | weights | dumbbells, hand weight, free weight, free weights, weights | gym | SCM | floor
barbell | weights | weight bar, barbells, olympic bar | gym | SCM | floor
kettlebell | weights | kettle bell, kettlebells | gym | SCM | floor
yoga_mat | sports_equipment | exercise mat, mat, gym mat, fitness mat, workout mat | gym bedroom | SC | floor
exercise_ball | sports_equipment | gym ball, swiss ball, stability ball, fitness ball, yoga ball, pilates ball | gym | SC | floor
hammer | hand_tool | mallet, sledgehammer, claw hammer | workshop garage | SCM | surface
saw | hand_tool | handsaw, hand saw, hacksaw, wood saw, crosscut saw | workshop garage | SCM | surface
screwdriver | hand_tool | screw driver, phillips screwdriver | workshop garage | SC | surface
wrench | hand_tool | spanner, monkey wrench, pliers, adjustable wrench | workshop garage | SCM | surface
drill | power_tool | power drill, electric drill, cordless drill, drilling machine | workshop garage | SCT | surface
wood_plank | building_material | plank, planks, lumber, timber, wooden board, wooden plank, beam, wood, plank of wood | workshop garage | SCMX | surface
nail | fastener | nails, screw, screws, tack, tacks, rivet | workshop garage | SM | surface
toolbox | container | tool box, tool kit, toolkit, tool case | workshop garage | SCM | surface
ladder | workshop_equipment | step ladder, stepladder, step stool ladder | workshop garage library | SCM | floor
sawhorse | workshop_equipment | saw horse, trestle, saw buck | workshop | SCM | floor
vise | hand_tool | vice, bench vise, bench vice, clamp | workshop | SCM | surface
paint_bucket | container | paint can, bucket, pail, paint tin, paint pot | workshop garage | SC | floor
broom | tool | mop, sweeper, broomstick, brush | workshop garage kitchen | SCM | floor
fire_extinguisher | safety_equipment | extinguisher, fire hose | office workshop garage kitchen | S | floor
bicycle | vehicle | bike, cycle, push bike, mountain bike, road bike | garage | SCT | floor
rug | textile | carpet, area rug, rugs, carpets, persian rug, doormat, door mat, floor mat, runner rug, throw rug | living_room bedroom kids_room lobby library home_office office | SCTM | floor
instrument_stand | music_equipment | stand, guitar stand, instrument stand, keyboard stand, amp stand | music_studio | SCM | floor
cake | food | birthday cake, cakes, pie, tart, cheesecake, cupcake, gateau, layer cake, sponge cake, chocolate cake | kids_room dining_room kitchen cafe living_room office | SCX | surface
vegetable | food | vegetables, veg, veggies, onion, onions, carrot, carrots, potato, potatoes, tomato, tomatoes, cucumber, cucumbers, zucchini, courgette, courgettes, leek, leeks, garlic, celery, lettuce, cabbage, broccoli, aubergine, eggplant, herbs, mushrooms, mushroom | kitchen | SC | surface
bread | food | loaf, loaf of bread, baguette, breads, bread loaf | kitchen dining_room cafe | SC | surface
chocolate_box | food | box of chocolates, chocolates, chocolate box, candy box, candies, candy, sweets, bonbons, pralines, truffles, chocolate | lobby living_room bedroom dining_room | SC | surface
film_negative | stationery | negative, negatives, photo negative, film negative, film strip, filmstrip, negative of a photo, contact sheet | gallery office home_office meeting_room | S | surface
pill_bottle | medicine | pill, pills, pill bottle, pillbox, pill box, medicine, medicine bottle, medication, capsule, capsules, aspirin, painkiller, painkillers, vitamins | bathroom bedroom kitchen | SC | surface
umbrella_stand | container | umbrella, umbrella holder, brolly stand | lobby | SC | floor
"""
# fmt: on

# Room types -> synonyms people write ("working shop" is how the paper names a workshop).
ROOM_ROWS: dict[str, tuple[str, ...]] = {
    "living_room": ("living room", "lounge", "sitting room", "family room", "parlour", "parlor", "den"),
    "bedroom": (
        "bed room",
        "sleeping room",
        "master bedroom",
        "guest room",
        "hotel room",
        "motel room",
        "hotel suite",
        "hospital room",
        "hospital ward",
        "dormitory",
    ),
    "kids_room": ("kids room", "children's room", "childrens room", "nursery", "playroom", "child's room"),
    "kitchen": ("kitchenette", "cookhouse"),
    "dining_room": ("dining room", "dining hall", "dinner room"),
    "bathroom": ("bath room", "restroom", "washroom", "toilet room", "wc room"),
    "office": ("workplace", "workroom", "cubicle", "office room", "bureau"),
    "home_office": ("home office", "study", "study room", "studio apartment office"),
    "meeting_room": ("meeting room", "conference room", "boardroom", "board room"),
    "classroom": ("class room", "school room", "schoolroom", "lecture room", "lecture hall", "school"),
    "music_studio": ("music studio", "recording studio", "studio", "music room", "rehearsal room"),
    "workshop": ("working shop", "work shop", "shop", "carpentry", "atelier", "woodshop"),
    "garage": ("car port", "carport", "shed", "tool shed"),
    "gallery": ("art gallery", "museum", "exhibition", "exhibition hall", "showroom"),
    "gym": ("gymnasium", "fitness room", "fitness center", "boxing gym", "health club", "weight room"),
    "library": ("reading room", "bookroom", "book room"),
    "cafe": ("coffee shop", "café", "coffeehouse", "coffee house", "canteen", "cafeteria"),
    "lobby": ("hall", "hallway", "foyer", "entrance hall", "reception", "waiting room", "corridor"),
}
